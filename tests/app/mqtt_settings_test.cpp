// The MQTT client's options from the configuration (README "Configuration", mqtt section), and
// where the password comes from: never the YAML.

#include "eip2mqtt/app/mqtt_settings.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace eip2mqtt::app {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

core::config::Config config() {
    core::config::Config c;
    c.gateway.id = "plant1";
    c.mqtt.url = "tcp://broker:1883";
    c.mqtt.username = "gw";
    return c;
}

class MqttSettingsTest : public ::testing::Test {
protected:
    void SetUp() override {
        ::unsetenv("EIP2MQTT_MQTT_PASSWORD");
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_mqtt_settings_" + std::string(info->name()) +
                                            "_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        ::unsetenv("EIP2MQTT_MQTT_PASSWORD");
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    fs::path dir_;
};

TEST_F(MqttSettingsTest, TheClientIdDefaultsToTheGatewaysId) {
    auto c = config();
    EXPECT_EQ(mqtt_client_options(c, "a").client_id, "eip2mqtt-plant1");
    c.mqtt.client_id = "scada-gw";
    EXPECT_EQ(mqtt_client_options(c, "a").client_id, "scada-gw");
}

TEST_F(MqttSettingsTest, ASessionThatDoesNotExpireIsACleanStart) {
    auto c = config();
    const auto clean = mqtt_client_options(c, "plant/_gateway/plant1/state");
    EXPECT_TRUE(clean.clean_start);
    EXPECT_EQ(clean.availability_topic, "plant/_gateway/plant1/state");
    EXPECT_EQ(clean.url, "tcp://broker:1883");
    EXPECT_EQ(clean.username, "gw");
    c.mqtt.session_expiry = 3600s;
    const auto kept = mqtt_client_options(c, "a");
    EXPECT_FALSE(kept.clean_start);
    EXPECT_EQ(kept.session_expiry, 3600s);
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

}  // namespace
}  // namespace eip2mqtt::app
