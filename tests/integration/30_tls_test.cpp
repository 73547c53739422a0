// Security: TLS with server verification, client certificates, and password authentication
// against a real Mosquitto, with a test PKI made by the openssl command line.

#include <signal.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/tls_certs.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using namespace std::chrono_literals;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .timeout_ms(0)
                                     .topic("area/pump")
                                     .tag("SPEED", "0.0", "real")
                                     .str();

constexpr const char* user = "gateway";
constexpr const char* password = "s3cret-Pa55";

std::vector<std::byte> speed_datagram(std::uint16_t rid, float speed) {
    return DatagramBuilder("10.0.0.2", 7, 4)
        .request_id(rid)
        .set("0.0", TagType::real, speed)
        .build();
}

class TlsTest : public GatewayTest {
protected:
    void SetUp() override { certs_ = std::make_unique<TlsCerts>(pki_.path()); }

    /// A broker whose secure listener speaks TLS with `cert`/`key` and wants `user`/`password`.
    GatewayOptions secure_broker(const std::string& cert, const std::string& key,
                                 bool require_certificate = false) const {
        GatewayOptions options;
        options.secure = true;
        options.broker.tls = MosquittoTls{certs_->ca_cert, cert, key, require_certificate};
        options.broker.users = {{user, password}};
        return options;
    }

    /// Writes the password to a file with `mode`; returns its path.
    std::string password_file(const std::string& content, mode_t mode) const {
        const auto path = pki_.write("mqtt-password", content + "\n");
        ::chmod(path.c_str(), mode);
        return path;
    }

    /// The mqtt section's keys for TLS and authentication.
    std::string mqtt_keys(const std::string& tls, const std::string& password_path = "") const {
        std::string keys = "  username: " + std::string(user) + "\n  tls: " + tls + "\n";
        if (!password_path.empty()) keys += "  password_file: " + password_path + "\n";
        return keys;
    }
    std::string verified_tls() const {
        return "{ ca_file: " + certs_->ca_cert + ", verify: true }";
    }

    /// The gateway values flow: one datagram in, its value out.
    void expect_values_flow() {
        send(speed_datagram(1, 1450.5f));
        expect_field(topic("area/pump/SPEED"), "value", "1450.5");
    }

    /// Waits for the gateway's "cannot connect" line, returns it, and checks it never came
    /// online (the failure is reported after its first attempt).
    std::string expect_refused() {
        EXPECT_TRUE(gateway_->wait_for_output("MQTT cannot connect", 20s))
            << "no connection failure logged; exit status " << gateway_->wait(0ms).value_or(-1)
            << "; output:\n"
            << gateway_->output();
        const auto output = gateway_->output();
        const auto at = output.find("MQTT cannot connect");
        const auto line =
            at == std::string::npos ? std::string() : output.substr(at, output.find('\n', at) - at);
        EXPECT_FALSE(recorder_->wait_for_message(
            availability_topic(), [](const std::string& p) { return p == "online"; }, 1s))
            << "the gateway came online";
        EXPECT_TRUE(gateway_->running()) << "the gateway should keep retrying";
        return line;
    }

    TempDir pki_;
    std::unique_ptr<TlsCerts> certs_;
};

TEST_F(TlsTest, VerifiedServerAndPasswordFileCarryValues) {
    start(one_exchange, mqtt_keys(verified_tls(), password_file(password, 0600)),
          secure_broker(certs_->server_cert, certs_->server_key));
    expect_values_flow();
    EXPECT_EQ(gateway_->output().find("readable by others"), std::string::npos);
    EXPECT_NE(broker_->log().find("u'" + std::string(user) + "'"), std::string::npos)
        << "the broker did not see the gateway's user name";
}

TEST_F(TlsTest, PasswordFromTheEnvironment) {
    auto options = secure_broker(certs_->server_cert, certs_->server_key);
    options.env = {{"EIP2MQTT_MQTT_PASSWORD", password}};
    start(one_exchange, mqtt_keys(verified_tls()), options);
    expect_values_flow();
}

TEST_F(TlsTest, ServerSignedByAnotherCaIsRefused) {
    auto options = secure_broker(certs_->other_server_cert, certs_->other_server_key);
    options.wait_online = false;
    start(one_exchange, mqtt_keys(verified_tls(), password_file(password, 0600)), options);
    const auto line = expect_refused();
    EXPECT_NE(line.find("TLS handshake failed"), std::string::npos) << line;
    EXPECT_NE(line.find("ca_file"), std::string::npos) << line;
}

TEST_F(TlsTest, VerifyFalseAcceptsAnUntrustedServer) {
    start(one_exchange,
          mqtt_keys("{ ca_file: " + certs_->ca_cert + ", verify: false }",
                    password_file(password, 0600)),
          secure_broker(certs_->other_server_cert, certs_->other_server_key));
    expect_values_flow();
}

TEST_F(TlsTest, RequiredClientCertificateIsProvided) {
    const auto tls = "{ ca_file: " + certs_->ca_cert + ", cert_file: " + certs_->client_cert +
                     ", key_file: " + certs_->client_key + ", verify: true }";
    start(one_exchange, mqtt_keys(tls, password_file(password, 0600)),
          secure_broker(certs_->server_cert, certs_->server_key, true));
    expect_values_flow();
}

TEST_F(TlsTest, MissingClientCertificateIsRefused) {
    auto options = secure_broker(certs_->server_cert, certs_->server_key, true);
    options.wait_online = false;
    start(one_exchange, mqtt_keys(verified_tls(), password_file(password, 0600)), options);
    const auto line = expect_refused();
    EXPECT_NE(line.find("client certificate"), std::string::npos) << line;
}

TEST_F(TlsTest, WrongPasswordIsRefusedWithAClearReason) {
    auto options = secure_broker(certs_->server_cert, certs_->server_key);
    options.wait_online = false;
    start(one_exchange, mqtt_keys(verified_tls(), password_file("not-the-password", 0600)),
          options);
    const auto line = expect_refused();
    EXPECT_TRUE(line.find("Not authorized") != std::string::npos ||
                line.find("Bad user name or password") != std::string::npos)
        << line;
}

TEST_F(TlsTest, PasswordFileReadableByOthersIsWarnedAbout) {
    start(one_exchange, mqtt_keys(verified_tls(), password_file(password, 0644)),
          secure_broker(certs_->server_cert, certs_->server_key));
    EXPECT_TRUE(gateway_->wait_for_output("readable by others", 5s)) << gateway_->output();
    expect_values_flow();
}

TEST_F(TlsTest, AReloadThatChangesATlsFileIsRefusedAndNamesIt) {
    // The reload compared only whether a tls section was there: a new ca_file was "applied"
    // while the running connection kept the old one.
    start(one_exchange, mqtt_keys(verified_tls(), password_file(password, 0600)),
          secure_broker(certs_->server_cert, certs_->server_key));
    expect_values_flow();
    const auto other_ca = pki_.path() + "/other-ca.pem";
    std::filesystem::copy_file(certs_->ca_cert, other_ca);

    std::ifstream in(config_path_);
    std::stringstream text;
    text << in.rdbuf();
    auto content = text.str();
    const auto at = content.find(certs_->ca_cert);
    ASSERT_NE(at, std::string::npos) << content;
    std::ofstream(config_path_) << content.replace(at, certs_->ca_cert.size(), other_ca);
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("reload refused: mqtt.tls.ca_file needs a restart", 10s))
        << gateway_->output();
    EXPECT_EQ(gateway_->output().find("configuration applied"), std::string::npos);
    send(speed_datagram(2, 1451.5f));
    expect_field(topic("area/pump/SPEED"), "value", "1451.5");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
