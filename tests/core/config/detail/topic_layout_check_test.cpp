// validate(): topics laid out by a template, locations and tags' own topics, checked as they
// expand, collisions included (docs/configuration.md, "Topics and payloads").

#include <gtest/gtest.h>

#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

/// valid(), its tags laid out by asset: acme/site/{area}/{asset}/{tag}.
Config by_asset() {
    auto c = valid();
    c.mqtt.topic_template = "{base}/{area}/{asset}/{tag}";
    c.mqtt.marks.add("topic_template", at(next_line++, 3));
    c.gateway.location.levels = {{"area", "hall"}};
    c.gateway.marks.add("location", at(next_line++, 3));
    for (auto& e : c.exchanges) {
        e.spec.location.levels = {{"asset", e.spec.name}};
        e.marks.add("location", at(next_line++, 5));
    }
    return c;
}

std::string messages(const Diagnostics& d) {
    std::string out;
    for (const auto& x : d) out += x.message + "\n";
    return out;
}

TEST(TopicLayout, AssetPathsThatDoNotMeetAreValid) {
    const auto c = by_asset();
    EXPECT_EQ(messages(validate(c)), "");
    const auto plans = make_plans(c);
    EXPECT_EQ(plans[0].tag_topic(plans[0].tags[1]), "acme/site/hall/turbine1/PRESSAO");
    EXPECT_EQ(plans[1].tag_topic(plans[1].tags[0]), "acme/site/hall/setpoints/SPEED_SP");
}

TEST(TopicLayout, ATemplateThatDoesNotParseIsRefusedAtItsKey) {
    auto c = by_asset();
    c.mqtt.topic_template = "{base}/{area}/{asset}";
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("topic_template").line);
    EXPECT_TRUE(mentions(d, "has no {tag}")) << d.message;
}

TEST(TopicLayout, APlaceholderNoLocationHasIsRefused) {
    auto c = by_asset();
    c.mqtt.topic_template = "{base}/{aera}/{asset}/{tag}";
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("topic_template").line);
    EXPECT_EQ(d.message,
              "topic_template's placeholder {aera} is a key of no location (of the gateway, an "
              "exchange or a tag)");
}

TEST(TopicLayout, LocationKeysAndValuesMustBeTopicLevels) {
    auto c = by_asset();
    c.exchanges[0].spec.location.levels = {{"asset", "t1//x"}};
    c.exchanges[1].spec.location.levels = {{"tag", "x"}};
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u) << messages(d);
    EXPECT_EQ(d[0].mark.line, c.exchanges[0].marks.of("location").line);
    EXPECT_EQ(d[0].message,
              "exchange 'turbine1': location asset 't1//x' has an empty level (leading, trailing "
              "or double '/')");
    EXPECT_EQ(d[1].message,
              "exchange 'setpoints': location key 'tag' is a placeholder of the gateway's own");
}

TEST(TopicLayout, ALevelTheGatewayKeepsForItselfIsRefusedWhereverItComesFrom) {
    auto c = by_asset();
    c.exchanges[0].spec.location.levels = {{"asset", "_status"}};
    auto d = validate(c);
    ASSERT_EQ(d.size(), 2u) << messages(d);  // both tags of turbine1
    EXPECT_EQ(d[0].mark.line, c.exchanges[0].tags[0].marks.of("name").line);
    EXPECT_EQ(d[0].message,
              "tag 'RUNNING' of exchange 'turbine1' gets topic 'acme/site/hall/_status/RUNNING', "
              "which has a level '_status', kept for the gateway's own topics ('set' and levels "
              "starting with '_')");
    c = by_asset();
    c.exchanges[1].tags[0].spec.mutable_extras().topic = "x/set/y";
    c.exchanges[1].tags[0].marks.add("topic", at(next_line++, 9));
    d = validate(c);
    ASSERT_EQ(d.size(), 1u) << messages(d);
    EXPECT_EQ(d[0].mark.line, c.exchanges[1].tags[0].marks.of("topic").line);
    EXPECT_TRUE(mentions(d[0], "has a level 'set'")) << d[0].message;
}

TEST(TopicLayout, TwoTagsOnOneExpandedTopicAreRefusedNamingBoth) {
    auto c = by_asset();
    // Both exchanges' tags at hall/pump: turbine1's PRESSAO and setpoints' renamed tag.
    c.exchanges[0].spec.location.levels = {{"asset", "pump"}};
    c.exchanges[1].spec.location.levels = {{"asset", "pump"}};
    auto& renamed = c.exchanges[1].tags[0];
    renamed.spec.mutable_extras().topic_name = "PRESSAO";
    renamed.marks.add("topic_name", at(next_line++, 9));
    const auto d = only(validate(c));
    const auto& first = c.exchanges[0].tags[1].marks.of("name");
    EXPECT_EQ(d.mark.line, renamed.marks.of("name").line);
    EXPECT_EQ(d.message,
              "tag 'SPEED_SP' of exchange 'setpoints' uses topic "
              "'acme/site/hall/pump/PRESSAO', already used by tag 'PRESSAO' of "
              "exchange 'turbine1' (line " +
                  std::to_string(first.line) + ", column " + std::to_string(first.column) + ")");
}

TEST(TopicLayout, ATagsTopicMeetingAnExchangesOwnTopicIsRefused) {
    auto c = by_asset();
    auto& tag = c.exchanges[1].tags[0];
    tag.spec.mutable_extras().topic = "acme/site/turbine1/_status";
    tag.marks.add("topic", at(next_line++, 9));
    // Both: the level, and the exchange's status topic it would take.
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u) << messages(d);
    EXPECT_TRUE(mentions(d[0], "already used by exchange 'turbine1'")) << messages(d);
    EXPECT_TRUE(mentions(d[1], "has a level '_status'")) << messages(d);
    // One the gateway never uses itself, but another exchange's `set` is.
    c = by_asset();
    c.exchanges[1].tags[0].spec.mutable_extras().topic = "acme/site/turbine1";
    c.exchanges[1].tags[0].marks.add("topic", at(next_line++, 9));
    const auto e = only(validate(c));
    EXPECT_TRUE(mentions(e,
                         "uses topic 'acme/site/turbine1/set', already used by exchange "
                         "'turbine1'"))
        << e.message;
}

TEST(TopicLayout, ATopicNameIsANameAndATopicIsNeverEmpty) {
    auto c = by_asset();
    auto& tag = c.exchanges[1].tags[0];
    tag.spec.mutable_extras().topic_name = "a/b";
    tag.marks.add("topic_name", at(next_line++, 9));
    auto d = only(validate(c));
    EXPECT_TRUE(mentions(d, "topic_name: tag name 'a/b' contains '/'")) << d.message;
    c = by_asset();
    c.exchanges[1].tags[0].marks.add("topic", at(next_line++, 9));
    d = only(validate(c));
    EXPECT_TRUE(mentions(d, "topic is empty")) << d.message;
}

TEST(TopicLayout, AnExpandedTopicPastMqttsLimitIsRefused) {
    auto c = by_asset();
    c.exchanges[0].spec.location.levels = {{"asset", std::string(65535, 'a')}};
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u) << messages(d).substr(0, 300);
    EXPECT_TRUE(mentions(d[0], "bytes long (MQTT allows 65535)")) << d[0].message.substr(0, 300);
}

TEST(TopicLayout, ATopicStartingWithADollarIsRefused) {
    auto c = by_asset();
    c.mqtt.topic_template = "{area}/{asset}/{tag}";
    c.gateway.location.levels = {{"area", "$SYS"}};
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 3u) << messages(d);
    EXPECT_TRUE(mentions(d[0], "starts with '$'")) << d[0].message;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
