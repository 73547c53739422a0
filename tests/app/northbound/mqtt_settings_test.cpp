// The MQTT client's options from the configuration (docs/configuration.md, mqtt section), and
// where the password comes from: never the YAML.

#include "eip2mqtt/app/northbound/mqtt_settings.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

core::config::Config config() {
    core::config::Config c;
    c.gateway.id = "plant1";
    c.mqtt.urls = {"tcp://broker:1883", "tcp://standby:1883"};
    c.mqtt.username = "gw";
    return c;
}

class MqttSettingsTest : public ::testing::Test {
protected:
    void SetUp() override {
        ::unsetenv("EIP2MQTT_MQTT_PASSWORD");
        ::unsetenv("CREDENTIALS_DIRECTORY");
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_mqtt_settings_" + std::string(info->name()) +
                                            "_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        ::unsetenv("EIP2MQTT_MQTT_PASSWORD");
        ::unsetenv("CREDENTIALS_DIRECTORY");
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    /// A credentials directory as systemd makes one for LoadCredential=, set in the environment.
    fs::path credentials(const std::string& name, const std::string& content) {
        const auto directory = dir_ / "credentials";
        fs::create_directories(directory);
        std::ofstream(directory / name) << content;
        ::setenv("CREDENTIALS_DIRECTORY", directory.c_str(), 1);
        return directory;
    }

    fs::path dir_;
};

TEST_F(MqttSettingsTest, TheClientIdDefaultsToTheGatewaysId) {
    auto c = config();
    EXPECT_EQ(mqtt_client_options(c, "a").client_id, "eip2mqtt-plant1");
    c.mqtt.client_id = "scada-gw";
    EXPECT_EQ(mqtt_client_options(c, "a").client_id, "scada-gw");
}

TEST_F(MqttSettingsTest, AnotherConnectionHasItsOwnBrokersIdAndLogNameAndMaySparkplug) {
    auto c = config();
    c.mqtt.name = "site";
    c.more_mqtt.push_back({});
    c.more_mqtt[0].name = "enterprise";
    c.more_mqtt[0].urls = {"ssl://uns:8883"};
    c.more_mqtt[0].username = "corp";
    c.more_mqtt[0].tls = core::config::TlsSection{"corp-ca.pem", "", "", true};
    c.more_mqtt[0].buffer_max_messages = 500;
    const auto enterprise = mqtt_client_options(c, "a", 1);
    EXPECT_EQ(enterprise.username, "corp");
    ASSERT_TRUE(enterprise.tls.has_value());
    EXPECT_EQ(enterprise.tls->ca_file, "corp-ca.pem");
    EXPECT_EQ(enterprise.buffer_max_messages, 500u);
    EXPECT_FALSE(mqtt_client_options(c, "a").tls.has_value());  // the first's: none
    EXPECT_EQ(enterprise.urls, std::vector<std::string>{"ssl://uns:8883"});
    EXPECT_EQ(enterprise.client_id, "eip2mqtt-plant1-enterprise");
    EXPECT_EQ(enterprise.log_name, "MQTT [enterprise]");
    EXPECT_EQ(mqtt_client_options(c, "a").log_name, "MQTT [site]");
    EXPECT_EQ(sparkplug_client_options(c, {}).client_id, "eip2mqtt-plant1-sparkplug");
    c.sparkplug.connection = "enterprise";
    EXPECT_EQ(sparkplug_client_options(c, {}).client_id, "eip2mqtt-plant1-enterprise-sparkplug");
    EXPECT_EQ(sparkplug_client_options(c, {}).urls, std::vector<std::string>{"ssl://uns:8883"});
    EXPECT_EQ(connections_summary(c),
              "mqtt connection site: tcp://broker:1883, then tcp://standby:1883, base topic "
              "eip2mqtt, takes writes\n"
              "mqtt connection enterprise: ssl://uns:8883, base topic eip2mqtt\n");
    EXPECT_EQ(brokers_line(c),
              "tcp://broker:1883, then tcp://standby:1883 and 1 more connection(s)");
}

TEST_F(MqttSettingsTest, PayloadsAreDescribedUnlessThePlantTradesItForThroughput) {
    auto c = config();
    EXPECT_TRUE(mqtt_client_options(c, "a").describe_payloads);
    c.mqtt.describe_payloads = false;
    EXPECT_FALSE(mqtt_client_options(c, "a").describe_payloads);
    // Sparkplug's protobuf is never described, whatever the setting.
    c.mqtt.describe_payloads = true;
    EXPECT_FALSE(sparkplug_client_options(c, {}).describe_payloads);
}

TEST_F(MqttSettingsTest, TheBrokerListReadsInItsOrder) {
    EXPECT_EQ(broker_list({"tcp://a:1883"}), "tcp://a:1883");
    EXPECT_EQ(broker_list({"tcp://a:1883", "tcp://b:1883", "tcp://c:1883"}),
              "tcp://a:1883, then tcp://b:1883, then tcp://c:1883");
}

TEST_F(MqttSettingsTest, ASessionThatDoesNotExpireIsACleanStart) {
    auto c = config();
    const auto clean = mqtt_client_options(c, "plant/_gateway/plant1/state");
    EXPECT_TRUE(clean.clean_start);
    EXPECT_EQ(clean.availability_topic, "plant/_gateway/plant1/state");
    EXPECT_EQ(clean.urls, (std::vector<std::string>{"tcp://broker:1883", "tcp://standby:1883"}));
    EXPECT_EQ(clean.username, "gw");
    c.mqtt.session_expiry = 3600s;
    const auto kept = mqtt_client_options(c, "a");
    EXPECT_FALSE(kept.clean_start);
    EXPECT_EQ(kept.session_expiry, 3600s);
}

// RabbitMQ before 3.13 keeps a QoS 1 subscription on its node: a clean 3.1.1 session subscribes
// at QoS 0 (it loses nothing by it); a kept session, MQTT 5 and Sparkplug's connection keep 1.
TEST_F(MqttSettingsTest, ACleanSessionOverMqtt311SubscribesAtQos0) {
    auto c = config();
    EXPECT_EQ(mqtt_client_options(c, "a").subscription_qos, 1);
    c.mqtt.version = 3;
    EXPECT_EQ(mqtt_client_options(c, "a").subscription_qos, 0);
    EXPECT_EQ(sparkplug_client_options(c, {}).subscription_qos, 1);
    c.mqtt.session_expiry = 3600s;
    EXPECT_EQ(mqtt_client_options(c, "a").subscription_qos, 1);
}

TEST_F(MqttSettingsTest, TlsFilesAndVerificationAreCarriedOver) {
    auto c = config();
    EXPECT_FALSE(mqtt_client_options(c, "a").tls.has_value());
    c.mqtt.tls = core::config::TlsSection{"/etc/ca.pem", "/etc/cert.pem", "/etc/key.pem", false};
    const auto tls = mqtt_client_options(c, "a").tls;
    ASSERT_TRUE(tls.has_value());
    EXPECT_EQ(tls->ca_file, "/etc/ca.pem");
    EXPECT_EQ(tls->cert_file, "/etc/cert.pem");
    EXPECT_EQ(tls->key_file, "/etc/key.pem");
    EXPECT_FALSE(tls->verify);
}

TEST_F(MqttSettingsTest, ThePasswordFileWinsOverTheEnvironmentAndOnlyItsFirstLineCounts) {
    const auto file = dir_ / "password";
    std::ofstream(file) << "s3cret\nsecond line\n";
    fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write);
    ::setenv("EIP2MQTT_MQTT_PASSWORD", "from-env", 1);
    auto c = config();
    EXPECT_EQ(mqtt_client_options(c, "a").password, "from-env");
    c.mqtt.password_file = file.string();
    EXPECT_EQ(mqtt_client_options(c, "a").password, "s3cret");
}

TEST_F(MqttSettingsTest, NoPasswordAnywhereIsAnEmptyOne) {
    EXPECT_EQ(read_mqtt_password(config().mqtt), "");
}

TEST_F(MqttSettingsTest, AnUnreadablePasswordFileIsAnErrorThatNamesIt) {
    auto c = config();
    c.mqtt.password_file = (dir_ / "missing").string();
    try {
        (void)read_mqtt_password(c.mqtt);
        FAIL() << "no error for a missing password file";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot read mqtt.password_file " + c.mqtt.password_file);
    }
}

// The packaged unit's LoadCredential=mqtt-password: read without any key in the YAML.
TEST_F(MqttSettingsTest, WithoutPasswordFileTheMqttPasswordCredentialWinsOverTheEnvironment) {
    ::setenv("EIP2MQTT_MQTT_PASSWORD", "from-env", 1);
    const auto directory = credentials("mqtt-password", "from-credential\nsecond line\n");
    EXPECT_EQ(mqtt_client_options(config(), "a").password, "from-credential");
    // A unit with other credentials but not this one: the environment is the alternative.
    fs::remove(directory / "mqtt-password");
    EXPECT_EQ(mqtt_client_options(config(), "a").password, "from-env");
}

TEST_F(MqttSettingsTest, APasswordFileWithoutASlashNamesACredential) {
    credentials("broker-b", "b-secret\n");
    auto c = config();
    c.mqtt.password_file = "broker-b";
    EXPECT_EQ(read_mqtt_password(c.mqtt), "b-secret");
}

TEST_F(MqttSettingsTest, APasswordFileWithASlashIsAPathUnderSystemdToo) {
    credentials("mqtt-password", "from-credential\n");
    const auto file = dir_ / "password";
    std::ofstream(file) << "from-file\n";
    auto c = config();
    c.mqtt.password_file = file.string();
    EXPECT_EQ(read_mqtt_password(c.mqtt), "from-file");
}

TEST_F(MqttSettingsTest, AMissingCredentialIsAnErrorThatNamesTheUnitSetting) {
    const auto directory = credentials("mqtt-password", "unused\n");
    auto c = config();
    c.mqtt.password_file = "broker-b";
    try {
        (void)read_mqtt_password(c.mqtt);
        FAIL() << "no error for a missing credential";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "cannot read mqtt.password_file: the systemd credential broker-b (" +
                      (directory / "broker-b").string() +
                      "); the unit needs LoadCredential=broker-b");
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
