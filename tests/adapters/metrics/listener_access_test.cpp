// Who may read the metrics listener: with a password, every path but /healthz and /readyz asks
// for it (401 with a Basic challenge), /metrics and the pages alike; with TLS, it speaks HTTPS
// with the configured certificate, which a client trusting the test CA verifies, and one
// trusting another CA refuses.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/core/net/basic_auth.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/tls_certs.hpp"

namespace eip2mqtt::adapters::metrics {
namespace EIP2MQTT_THIS_FILE {

using test::http_request;
using test::status_and_body;

const std::string good_credentials =
    "Authorization: " + core::net::basic_authorization("ops", "s3cret") + "\r\n";

PrometheusEndpoint with_password() {
    return PrometheusEndpoint("127.0.0.1:0", PrometheusEndpoint::default_liveness_timeout,
                              clock::system_clock(),
                              {core::net::basic_authorization("ops", "s3cret"), "", ""});
}

std::string status_of(std::uint16_t port, const std::string& path, const std::string& headers) {
    return status_and_body(http_request(port, "GET", path, headers)).first;
}

TEST(ListenerAccess, APasswordIsAskedEverywhereButHealth) {
    auto endpoint = with_password();
    endpoint.update({});
    endpoint.serve_pages([](std::string_view) {
        return std::optional<HttpAnswer>(HttpAnswer{200, "text/plain", "page"});
    });
    const auto port = endpoint.port();
    for (const std::string path : {"/metrics", "/", "/api/status"}) {
        const auto refused = http_request(port, "GET", path);
        EXPECT_EQ(status_and_body(refused).first, "401") << path;
        EXPECT_NE(refused.find("WWW-Authenticate: Basic realm=\"eip2mqtt\""), std::string::npos)
            << refused;
        EXPECT_EQ(
            status_of(port, path,
                      "Authorization: " + core::net::basic_authorization("ops", "wrong") + "\r\n"),
            "401")
            << path;
        EXPECT_EQ(status_of(port, path, "Authorization: Basic\r\n"), "401") << path;
        EXPECT_EQ(status_of(port, path, good_credentials), "200") << path;
    }
    // Probes never carry a password: the health of a listener is never hidden.
    EXPECT_EQ(status_of(port, "/healthz", ""), "200");
    EXPECT_EQ(status_of(port, "/readyz", ""), "503");  // no exchange, no broker: not ready
}

class ListenerTlsTest : public ::testing::Test {
protected:
    ListenerTlsTest()
        : dir_(std::filesystem::temp_directory_path() /
               ("eip2mqtt_listener_tls_" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(dir_);
        certs_ = std::make_unique<test::TlsCerts>(dir_.string());
    }
    ~ListenerTlsTest() override { std::filesystem::remove_all(dir_); }

    std::filesystem::path dir_;
    std::unique_ptr<test::TlsCerts> certs_;
};

TEST_F(ListenerTlsTest, ItSpeaksHttpsWithItsCertificateAndAsksThePasswordInside) {
    PrometheusEndpoint endpoint(
        "127.0.0.1:0", PrometheusEndpoint::default_liveness_timeout, clock::system_clock(),
        {core::net::basic_authorization("ops", "s3cret"), certs_->server_cert, certs_->server_key});
    endpoint.update({});
    const auto port = endpoint.port();
    const auto [verified, metrics] =
        test::https_get(port, "/metrics", certs_->ca_cert, good_credentials);
    EXPECT_TRUE(verified);
    EXPECT_EQ(status_and_body(metrics).first, "200") << metrics;
    EXPECT_NE(metrics.find("eip2mqtt_mqtt_connected 0"), std::string::npos) << metrics;
    EXPECT_EQ(status_and_body(test::https_get(port, "/metrics", certs_->ca_cert).second).first,
              "401");
    EXPECT_EQ(status_and_body(test::https_get(port, "/healthz", certs_->ca_cert).second).first,
              "200");
    // A client that trusts another CA does not get through the handshake.
    EXPECT_FALSE(test::https_get(port, "/healthz", certs_->other_ca_cert).first);
    // Plain HTTP to it gets no page.
    EXPECT_EQ(status_and_body(http_request(port, "GET", "/healthz")).first, "");
}

TEST_F(ListenerTlsTest, AKeyThatIsNotTheCertificatesIsAStartUpErrorThatSaysSo) {
    try {
        PrometheusEndpoint endpoint("127.0.0.1:0", PrometheusEndpoint::default_liveness_timeout,
                                    clock::system_clock(),
                                    {"", certs_->server_cert, certs_->other_server_key});
        FAIL() << "started with a key of another certificate";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot load the key"), std::string::npos) << e.what();
    }
    try {
        PrometheusEndpoint endpoint("127.0.0.1:0", PrometheusEndpoint::default_liveness_timeout,
                                    clock::system_clock(),
                                    {"", (dir_ / "missing.pem").string(), certs_->server_key});
        FAIL() << "started without its certificate";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot load the certificate"), std::string::npos)
            << e.what();
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::metrics
