#include "adapters/mqtt/detail/connect_options.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

ClientOptions options_for(int version) {
    ClientOptions options;
    options.urls = {"tcp://localhost:1883"};
    options.version = version;
    options.clean_start = true;
    options.keepalive = 20s;
    options.availability_topic = "plant/_gateway/gw/state";
    return options;
}

TEST(ConnectOptions, Mqtt5WithSessionExpiryCredentialsAndTheOfflineWill) {
    auto options = options_for(5);
    options.clean_start = false;
    options.session_expiry = std::chrono::seconds(3600);
    options.username = "gateway";
    options.password = "secret";
    ::mqtt::connect_options co;
    configure_connect_options(co, options, parse_broker_url(options.urls.front()), 10s);
    EXPECT_EQ(co.get_mqtt_version(), MQTTVERSION_5);
    EXPECT_FALSE(co.is_clean_start());
    EXPECT_EQ(::mqtt::get<int>(co.get_properties(), ::mqtt::property::SESSION_EXPIRY_INTERVAL),
              3600);
    EXPECT_EQ(co.get_keep_alive_interval(), 20s);
    EXPECT_EQ(co.get_connect_timeout(), 10s);
    EXPECT_FALSE(co.get_automatic_reconnect());
    EXPECT_EQ(co.get_user_name(), "gateway");
    EXPECT_EQ(co.get_password_str(), "secret");
    ASSERT_NE(co.get_will_message(), nullptr);
    EXPECT_EQ(co.get_will_message()->get_topic(), "plant/_gateway/gw/state");
    EXPECT_EQ(co.get_will_message()->get_payload_str(), "offline");
    EXPECT_TRUE(co.get_will_message()->is_retained());
    EXPECT_TRUE(co.get_ssl_options().get_trust_store().empty());
}

TEST(ConnectOptions, Mqtt311CleanSessionNoCredentialsNoWill) {
    auto options = options_for(3);
    options.availability_topic.clear();
    ::mqtt::connect_options co;
    configure_connect_options(co, options, parse_broker_url(options.urls.front()), 10s);
    EXPECT_EQ(co.get_mqtt_version(), MQTTVERSION_3_1_1);
    EXPECT_TRUE(co.is_clean_session());
    EXPECT_TRUE(co.get_user_name().empty());
    EXPECT_TRUE(co.get_will_message() == nullptr || co.get_will_message()->get_topic().empty());
}

TEST(ConnectOptions, TlsFromTheSchemeWithTheGivenFiles) {
    auto options = options_for(5);
    options.urls = {"ssl://broker:8883"};
    options.tls = TlsOptions{"/etc/ssl/ca.pem", "client.pem", "client.key", true};
    ::mqtt::connect_options co;
    configure_connect_options(co, options, parse_broker_url(options.urls.front()), 10s);
    EXPECT_EQ(co.get_ssl_options().get_trust_store(), "/etc/ssl/ca.pem");
    EXPECT_EQ(co.get_ssl_options().get_key_store(), "client.pem");
    EXPECT_EQ(co.get_ssl_options().get_private_key(), "client.key");
    EXPECT_TRUE(co.get_ssl_options().get_enable_server_cert_auth());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
