#include "adapters/mqtt/detail/broker_url.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(BrokerUrl, HostAndPortOfEachScheme) {
    const auto plain = parse_broker_url("tcp://broker.plant:1884");
    ASSERT_TRUE(plain.has_value());
    EXPECT_EQ(plain->host, "broker.plant");
    EXPECT_EQ(plain->port, 1884);
    EXPECT_FALSE(plain->tls);
    EXPECT_EQ(parse_broker_url("tcp://localhost")->port, 1883);
    EXPECT_EQ(parse_broker_url("mqtt://localhost")->port, 1883);
    EXPECT_EQ(parse_broker_url("ssl://localhost")->port, 8883);
    EXPECT_TRUE(parse_broker_url("ssl://localhost")->tls);
    EXPECT_TRUE(parse_broker_url("mqtts://localhost")->tls);
    EXPECT_EQ(parse_broker_url("ws://localhost/mqtt")->port, 80);
    EXPECT_FALSE(parse_broker_url("ws://localhost/mqtt")->tls);
    const auto wss = parse_broker_url("wss://broker:9443/mqtt");
    EXPECT_EQ(wss->host, "broker");
    EXPECT_EQ(wss->port, 9443);
    EXPECT_TRUE(wss->tls);
}

TEST(BrokerUrl, BracketedIpv6) {
    const auto v6 = parse_broker_url("tcp://[::1]:1885");
    ASSERT_TRUE(v6.has_value());
    EXPECT_EQ(v6->host, "::1");
    EXPECT_EQ(v6->port, 1885);
    EXPECT_EQ(parse_broker_url("ssl://[fe80::1]")->port, 8883);
}

TEST(BrokerUrl, NotAUrl) {
    EXPECT_FALSE(parse_broker_url("localhost:1883").has_value());
    EXPECT_FALSE(parse_broker_url("tcp://[::1:1883").has_value());
    EXPECT_FALSE(parse_broker_url("tcp://host:0").has_value());
    EXPECT_FALSE(parse_broker_url("tcp://host:65536").has_value());
    EXPECT_FALSE(parse_broker_url("tcp://host:port").has_value());
}

TEST(BrokerUrl, TheNextBrokerWrapsAroundTheList) {
    EXPECT_EQ(next_broker(0, 1), 0u);  // a single broker: always it
    EXPECT_EQ(next_broker(0, 3), 1u);
    EXPECT_EQ(next_broker(1, 3), 2u);
    EXPECT_EQ(next_broker(2, 3), 0u);  // after the last, the first
    std::size_t broker = 0;
    std::vector<std::size_t> tried;
    for (int attempt = 0; attempt < 5; ++attempt) {
        tried.push_back(broker);
        broker = next_broker(broker, 2);
    }
    EXPECT_EQ(tried, (std::vector<std::size_t>{0, 1, 0, 1, 0}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
