// The MQTT 5 properties of a publication (docs/mqtt-api.md, "MQTT 5 metadata"), as handed to
// Paho: nothing over MQTT 3.1.1, a content type and format indicator when the client describes
// its payloads, user properties and expiry as the message asks, and a live value's topic given
// an alias on its first publication of a connection and sent alone after it.

#include "adapters/mqtt/detail/publish_properties.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

Message data(std::string topic) {
    Message m;
    m.topic = std::move(topic);
    m.payload = R"({"value":1})";
    m.qos = 1;
    m.live = true;
    return m;
}

int alias_of(const ::mqtt::message_ptr& m) {
    const auto& p = m->get_properties();
    return p.contains(::mqtt::property::TOPIC_ALIAS)
               ? ::mqtt::get<std::uint16_t>(p, ::mqtt::property::TOPIC_ALIAS)
               : 0;
}

TEST(PublishProperties, MqttThreeCarriesNone) {
    ClientOptions options;
    options.version = 3;
    options.describe_payloads = true;
    options.topic_aliases = true;
    PublishProperties properties(options);
    properties.on_connected(10);
    auto m = data("a/b");
    add_user_property(m, "unit", "rpm");
    const auto out = properties.to_paho(m);
    EXPECT_EQ(out->get_topic(), "a/b");
    EXPECT_TRUE(out->get_properties().empty());
}

TEST(PublishProperties, TheDefaultSaysOnlyTheTypeOfEachPayload) {
    ClientOptions options;
    options.describe_payloads = true;
    PublishProperties properties(options);
    const auto out = properties.to_paho(data("a/b"));
    EXPECT_EQ(out->get_topic(), "a/b");
    EXPECT_EQ(out->get_payload_str(), R"({"value":1})");
    EXPECT_EQ(out->get_qos(), 1);
    const auto& p = out->get_properties();
    EXPECT_EQ(p.size(), 2u);
    EXPECT_EQ(::mqtt::get<std::string>(p, ::mqtt::property::CONTENT_TYPE), "application/json");
    EXPECT_EQ(::mqtt::get<std::uint8_t>(p, ::mqtt::property::PAYLOAD_FORMAT_INDICATOR), 1);
    auto state = data("a/state");
    state.text = true;
    state.retain = true;
    const auto said = properties.to_paho(state);
    EXPECT_TRUE(said->is_retained());
    EXPECT_EQ(said->get_properties().size(), 2u);
    EXPECT_EQ(::mqtt::get<std::string>(said->get_properties(), ::mqtt::property::CONTENT_TYPE),
              "text/plain");
}

TEST(PublishProperties, ADescribedLiveValueSaysItsTypeItsPropertiesAndItsExpiry) {
    ClientOptions options;
    options.describe_payloads = true;
    options.message_expiry = std::chrono::seconds(600);
    PublishProperties properties(options);
    auto m = data("a/b");
    add_user_property(m, "unit", "rpm");
    add_user_property(m, "quality", "good");
    const auto out = properties.to_paho(m);
    const auto& p = out->get_properties();
    EXPECT_EQ(::mqtt::get<std::string>(p, ::mqtt::property::CONTENT_TYPE), "application/json");
    EXPECT_EQ(::mqtt::get<std::uint8_t>(p, ::mqtt::property::PAYLOAD_FORMAT_INDICATOR), 1);
    EXPECT_EQ(::mqtt::get<std::uint32_t>(p, ::mqtt::property::MESSAGE_EXPIRY_INTERVAL), 600u);
    ASSERT_EQ(p.count(::mqtt::property::USER_PROPERTY), 2u);
    EXPECT_EQ(::mqtt::get<::mqtt::string_pair>(p, ::mqtt::property::USER_PROPERTY, 1),
              (::mqtt::string_pair{"quality", "good"}));
    // Text says so; what is not live never expires.
    auto state = data("a/state");
    state.text = true;
    state.live = false;
    const auto said = properties.to_paho(state);
    const auto& q = said->get_properties();
    EXPECT_EQ(::mqtt::get<std::string>(q, ::mqtt::property::CONTENT_TYPE), "text/plain");
    EXPECT_FALSE(q.contains(::mqtt::property::MESSAGE_EXPIRY_INTERVAL));
}

TEST(PublishProperties, ATopicIsNamedOnceThenSentByItsAliasUpToTheBrokersMaximum) {
    ClientOptions options;
    options.topic_aliases = true;
    PublishProperties properties(options);
    properties.on_connected(2);
    const auto first = properties.to_paho(data("plant/area/asset/SPEED"));
    EXPECT_EQ(first->get_topic(), "plant/area/asset/SPEED");
    EXPECT_EQ(alias_of(first), 1);
    const auto again = properties.to_paho(data("plant/area/asset/SPEED"));
    EXPECT_EQ(again->get_topic(), "");
    EXPECT_EQ(alias_of(again), 1);
    EXPECT_EQ(alias_of(properties.to_paho(data("plant/area/asset/FLOW"))), 2);
    // The broker takes two: a third topic goes by name, every time.
    const auto third = properties.to_paho(data("plant/area/asset/LEVEL"));
    EXPECT_EQ(third->get_topic(), "plant/area/asset/LEVEL");
    EXPECT_EQ(alias_of(third), 0);
    EXPECT_EQ(properties.to_paho(data("plant/area/asset/LEVEL"))->get_topic(),
              "plant/area/asset/LEVEL");
    EXPECT_EQ(properties.aliased(), 1u);
    // A new connection knows none of them.
    properties.on_connected(2);
    const auto renewed = properties.to_paho(data("plant/area/asset/SPEED"));
    EXPECT_EQ(renewed->get_topic(), "plant/area/asset/SPEED");
    EXPECT_EQ(alias_of(renewed), 1);
}

TEST(PublishProperties, OnlyLiveValuesTakeTheBrokersFewAliases) {
    ClientOptions options;
    options.topic_aliases = true;
    PublishProperties properties(options);
    properties.on_connected(1);
    // The state and `_status`, sent before any value, leave the one alias to the value.
    for (const char* topic : {"b/_gateway/g/state", "b/e1/_status", "b/e1/_status"}) {
        auto said = data(topic);
        said.live = false;
        const auto out = properties.to_paho(said);
        EXPECT_EQ(out->get_topic(), topic);
        EXPECT_EQ(alias_of(out), 0);
    }
    EXPECT_EQ(alias_of(properties.to_paho(data("plant/area/asset/SPEED"))), 1);
    EXPECT_EQ(properties.to_paho(data("plant/area/asset/SPEED"))->get_topic(), "");
}

TEST(PublishProperties, NoAliasWhereTheBrokerTakesNone) {
    ClientOptions options;
    options.topic_aliases = true;
    PublishProperties properties(options);
    properties.on_connected(0);
    for (int i = 0; i < 2; ++i) {
        const auto out = properties.to_paho(data("a/b"));
        EXPECT_EQ(out->get_topic(), "a/b");
        EXPECT_EQ(alias_of(out), 0);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
