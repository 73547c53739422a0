// `mqtt` as a list of connections (docs/configuration.md, "Several brokers at once"): each read
// as a lone `mqtt` is, the first the main one; names, base topics, the tags' layout and
// `sparkplug.connection` checked across the list.

#include <gtest/gtest.h>

#include <string>

#include "tests/adapters/yaml/loading.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

const std::string two_connections =
    "mqtt:\n"
    "  - name: site\n"
    "    url: [ tcp://edge1:1883, tcp://edge2:1883 ]\n"
    "    store_and_forward: { enabled: true }\n"
    "  - name: enterprise\n"
    "    url: ssl://uns.example:8883\n"
    "    base_topic: acme/plant1\n"
    "    payload: value\n"
    "    writes: true\n"
    "    store_and_forward: { enabled: true, max_mb: 512 }\n";

TEST(MqttConnections, EachEntryIsAConnectionTheFirstTheMainOne) {
    const auto config = good(two_connections + minimal_exchange);
    EXPECT_EQ(config.mqtt.name, "site");
    EXPECT_EQ(config.mqtt.urls.size(), 2u);
    ASSERT_EQ(config.more_mqtt.size(), 1u);
    const auto& enterprise = config.more_mqtt[0];
    EXPECT_EQ(enterprise.name, "enterprise");
    EXPECT_EQ(enterprise.base_topic, "acme/plant1");
    EXPECT_EQ(enterprise.payload, core::config::PayloadFormat::value);
    EXPECT_EQ(enterprise.store_and_forward.max_mb, 512u);
    EXPECT_TRUE(core::config::takes_writes(config.mqtt, 0));
    EXPECT_TRUE(core::config::takes_writes(enterprise, 1));
}

TEST(MqttConnections, OnlyTheFirstTakesWritesUnlessTold) {
    const auto config =
        good("mqtt:\n  - { name: a }\n  - { name: b, base_topic: other }\n" + minimal_exchange);
    EXPECT_TRUE(core::config::takes_writes(config.mqtt, 0));
    EXPECT_FALSE(core::config::takes_writes(config.more_mqtt[0], 1));
    const auto first_off = good("mqtt:\n  writes: false\n" + minimal_exchange);
    EXPECT_FALSE(core::config::takes_writes(first_off.mqtt, 0));
}

TEST(MqttConnections, AListOfOneIsTheLoneConnection) {
    const auto config = good("mqtt:\n  - url: tcp://a:1883\n" + minimal_exchange);
    EXPECT_TRUE(config.more_mqtt.empty());
    EXPECT_EQ(core::config::connection_name(config.mqtt), "mqtt");
}

TEST(MqttConnections, EveryConnectionOfAListNamesItselfOnce) {
    const auto unnamed =
        dump(bad("mqtt:\n  - { name: a }\n  - { url: tcp://b:1 }\n" + minimal_exchange));
    EXPECT_NE(unnamed.find("test.yaml:3:5: mqtt connection 2 has no 'name'"), std::string::npos)
        << unnamed;
    const auto twice =
        dump(bad("mqtt:\n  - { name: a }\n  - { name: a, base_topic: b }\n" + minimal_exchange));
    EXPECT_NE(twice.find("test.yaml:3:7: mqtt name 'a' names two connections"), std::string::npos)
        << twice;
    const auto slash = dump(bad("mqtt:\n  - { name: a/b }\n  - { name: c }\n" + minimal_exchange));
    EXPECT_NE(slash.find("mqtt name 'a/b' may hold only letters"), std::string::npos) << slash;
}

TEST(MqttConnections, AnEntryIsCheckedAsALoneConnectionIs) {
    const auto text = dump(
        bad("mqtt:\n  - { name: a }\n  - { name: b, qos: 3, colour: red }\n" + minimal_exchange));
    EXPECT_NE(text.find("mqtt qos 3 is not 0, 1 or 2"), std::string::npos) << text;
    EXPECT_NE(text.find("unknown key 'colour' in mqtt connection 2"), std::string::npos) << text;
}

TEST(MqttConnections, TheTagsLayoutIsTheFirstConnections) {
    const auto text =
        dump(bad("mqtt:\n  - { name: a }\n  - { name: b, topic_template: "
                 "\"{base}/x/{tag}\" }\n" +
                 minimal_exchange));
    EXPECT_NE(text.find("topic_template is the first connection's"), std::string::npos) << text;
}

TEST(MqttConnections, BaseTopicsLieApartOrAreOne) {
    const auto nested =
        dump(bad("mqtt:\n  - { name: a, base_topic: plant }\n  - { name: b, "
                 "base_topic: plant/enterprise }\n" +
                 minimal_exchange));
    EXPECT_NE(nested.find("lie one under the other"), std::string::npos) << nested;
    good("mqtt:\n  - { name: a, base_topic: plant }\n  - { name: b, base_topic: plant }\n" +
         minimal_exchange);
    good("mqtt:\n  - { name: a, base_topic: plant }\n  - { name: b, base_topic: plantx }\n" +
         minimal_exchange);
}

TEST(MqttConnections, SparkplugRunsOnTheConnectionItNames) {
    const auto config =
        good(two_connections + "sparkplug:\n  group_id: g\n  connection: enterprise\n" +
             minimal_exchange);
    EXPECT_EQ(core::config::sparkplug_connection(config), 1u);
    const auto text = dump(bad(two_connections + "sparkplug:\n  group_id: g\n  connection: nope\n" +
                               minimal_exchange));
    EXPECT_NE(text.find("sparkplug connection 'nope' is not the name of an mqtt connection"),
              std::string::npos)
        << text;
}

TEST(MqttConnections, AnEmptyListIsRefused) {
    const auto text = dump(bad("mqtt: []\n" + minimal_exchange));
    EXPECT_NE(text.find("mqtt is an empty list"), std::string::npos) << text;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
