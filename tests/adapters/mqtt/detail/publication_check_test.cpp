#include "adapters/mqtt/detail/publication_check.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

Message message(std::string topic, std::string payload = "1") {
    Message m;
    m.topic = std::move(topic);
    m.payload = std::move(payload);
    return m;
}

TEST(PublicationCheck, OrdinaryPublicationsPass) {
    EXPECT_EQ(publication_problem(message("acme/t1/SPEED"), max_mqtt_packet_size), "");
    EXPECT_EQ(publication_problem(message("acme/t1/SPEED", ""), max_mqtt_packet_size), "");
}

TEST(PublicationCheck, TopicsABrokerRefusesAreCaught) {
    EXPECT_EQ(publication_problem(message("rt/#"), max_mqtt_packet_size),
              "topic contains a wildcard ('+' or '#')");
    EXPECT_EQ(publication_problem(message(std::string(65536, 't')), max_mqtt_packet_size),
              "topic is 65536 bytes long (MQTT allows 65535)");
    EXPECT_EQ(publication_problem(message("a\xff"), max_mqtt_packet_size),
              "topic is not valid UTF-8");
    EXPECT_EQ(publication_problem(message(""), max_mqtt_packet_size), "topic is empty");
}

TEST(PublicationCheck, PacketsOverTheBrokersMaximumAreCaught) {
    EXPECT_EQ(publication_problem(message("t", std::string(1000, 'x')), 2000), "");
    EXPECT_EQ(publication_problem(message("t", std::string(2000, 'x')), 2000),
              "a packet of up to 2017 bytes (the broker takes 2000)");
    auto m = message("t");
    m.correlation_data.assign(65536, 'c');
    EXPECT_EQ(publication_problem(m, max_mqtt_packet_size),
              "correlation data of 65536 bytes (MQTT allows 65535)");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
