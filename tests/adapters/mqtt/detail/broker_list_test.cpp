// BrokerList: the brokers of ClientOptions::urls, tried in turn.

#include "adapters/mqtt/detail/broker_list.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(BrokerList, WalksTheUrlsInTurnAndBackToTheFirst) {
    const std::vector<std::string> urls{"tcp://a:1883", "ssl://b:8883"};
    BrokerList brokers(urls);
    EXPECT_EQ(brokers.url(), "tcp://a:1883");
    ASSERT_TRUE(brokers.endpoint());
    EXPECT_EQ(brokers.endpoint()->host, "a");
    brokers.move_to_next();
    EXPECT_EQ(brokers.url(), "ssl://b:8883");
    ASSERT_TRUE(brokers.endpoint());
    EXPECT_TRUE(brokers.endpoint()->tls);
    EXPECT_EQ(brokers.first_endpoint()->host, "a");
    brokers.move_to_next();
    EXPECT_EQ(brokers.url(), "tcp://a:1883");
}

TEST(BrokerList, AnUnknownUrlNamesNoEndpoint) {
    const std::vector<std::string> urls{"not a url"};
    BrokerList brokers(urls);
    EXPECT_FALSE(brokers.endpoint());
    brokers.move_to_next();
    EXPECT_EQ(brokers.url(), "not a url");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
