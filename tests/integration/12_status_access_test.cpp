// Who may read the status listener of a running gateway: metrics.auth's password (from a
// systemd credential, as the packaged unit passes it) asked on the API and /metrics, never on
// /healthz; metrics.tls serving it over HTTPS with the test CA's certificate.

#include <filesystem>
#include <memory>
#include <string>

#include "eip2mqtt/core/net/basic_auth.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/tls_certs.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

class StatusAccessTest : public GatewayTest {
protected:
    void SetUp() override {
        port_ = free_tcp_port();
        certs_ = std::make_unique<TlsCerts>(dir_.path());
        const auto credentials = dir_.path() + "/credentials";
        std::filesystem::create_directories(credentials);
        std::filesystem::permissions(
            dir_.write("credentials/status-password", "s3cret\n"),
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
        GatewayOptions options;
        options.env["CREDENTIALS_DIRECTORY"] = credentials;
        options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port_) +
                           "\n  auth: { username: ops, password_file: status-password }\n"
                           "  tls: { cert: " +
                           certs_->server_cert + ", key: " + certs_->server_key + " }\n";
        start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
                  .length(4)
                  .tag("SPEED", "0.0", "dint")
                  .str(),
              "", options);
    }

    /// GET `path` over HTTPS trusting the test CA, with `user`'s password when given: the code.
    std::string code(const std::string& path, const std::string& password = "") {
        const auto headers =
            password.empty()
                ? std::string()
                : "Authorization: " + core::net::basic_authorization("ops", password) + "\r\n";
        const auto [verified, response] = https_get(port_, path, certs_->ca_cert, headers);
        EXPECT_TRUE(verified) << path;
        return status_and_body(response).first;
    }

    std::uint16_t port_ = 0;
    std::unique_ptr<TlsCerts> certs_;
};

TEST_F(StatusAccessTest, ThePasswordOpensTheApiAndTheMetricsAndHealthNeedsNone) {
    EXPECT_EQ(code("/api/status"), "401");
    EXPECT_EQ(code("/api/status", "wrong"), "401");
    EXPECT_EQ(code("/api/status", "s3cret"), "200");
    EXPECT_EQ(code("/metrics"), "401");
    EXPECT_EQ(code("/metrics", "s3cret"), "200");
    EXPECT_EQ(code("/", "s3cret"), "200");
    // Health answers without asking (ok, or 503 until the loop's first report).
    const auto health = code("/healthz");
    EXPECT_TRUE(health == "200" || health == "503") << health;
    // Plain HTTP gets nothing from an HTTPS listener.
    EXPECT_EQ(status_and_body(http_get(port_, "/healthz")).first, "");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
