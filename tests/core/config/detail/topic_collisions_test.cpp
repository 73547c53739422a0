// validate(): topics claimed twice, across exchanges and their tags.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Validate, TwoExchangesOnOneTopic) {
    auto c = valid();
    c.exchanges[1].spec.topic = "turbine1";
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[1].marks.of("topic").line);
    EXPECT_TRUE(mentions(d, "exchange 'turbine1'"));
}

TEST(Validate, TagTopicCollidingAcrossExchanges) {
    // turbine1/PRESSAO/set (tag write topic) == exchange turbine1/PRESSAO's set topic.
    auto c = valid();
    c.exchanges[1].spec.topic = "turbine1/PRESSAO";
    const auto d = only(validate(c));
    EXPECT_TRUE(mentions(d, "turbine1/PRESSAO/set"));
}

TEST(Validate, TagTopicCollidingWithAnEarlierExchangesSetTopic) {
    // The exchange on turbine1/PRESSAO comes first: the tag's write topic is the one refused.
    auto c = valid();
    auto child = c.exchanges[1];
    child.spec.name = "child";
    child.spec.topic = "turbine1/PRESSAO";
    child.spec.exchange_id = 99;
    c.exchanges.insert(c.exchanges.begin(), child);
    const auto d = only(validate(c));
    EXPECT_TRUE(mentions(d,
                         "tag 'PRESSAO' of exchange 'turbine1' uses topic "
                         "'acme/site/turbine1/PRESSAO/set', already used by exchange 'child'"))
        << d.message;
}

/// An exchange `result_holder` on topic `topic`, with a tag named `result`.
ExchangeConfig result_holder(const std::string& topic) {
    auto e = exchange("result_holder", Direction::consume, 77);
    e.spec.topic = topic;
    e.tags.push_back(tag("result", 0, 0, TagType::int_));
    return e;
}

TEST(Validate, AnExchangesResultTopicCollidesWithATagNamedResultUnderItsSetLevel) {
    // acme/site/turbine1/set/result: turbine1's write results, and the topic of tag `result`
    // of an exchange on turbine1/set. The topic is refused for its `set` level, and the
    // collision is shown as well.
    auto c = valid();
    c.exchanges.push_back(result_holder("turbine1/set"));
    auto d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_TRUE(mentions(d[0], "has a level 'set'")) << d[0].message;
    EXPECT_EQ(d[1].mark.line, c.exchanges.back().tags[0].marks.of("name").line);
    EXPECT_EQ(d[1].message,
              "tag 'result' of exchange 'result_holder' uses topic "
              "'acme/site/turbine1/set/result', already used by exchange 'turbine1' (line " +
                  std::to_string(c.exchanges[0].marks.of("topic").line) + ", column " +
                  std::to_string(c.exchanges[0].marks.of("topic").column) + ")");

    // The other way round: the exchange's own claim is the one refused.
    c = valid();
    c.exchanges.insert(c.exchanges.begin(), result_holder("turbine1/set"));
    d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].mark.line, c.exchanges[1].marks.of("topic").line);  // turbine1's topic
    EXPECT_EQ(d[0].message,
              "exchange 'turbine1' uses topic 'acme/site/turbine1/set/result', already used by "
              "tag 'result' of exchange 'result_holder' (line " +
                  std::to_string(c.exchanges[0].tags[0].marks.of("name").line) + ", column " +
                  std::to_string(c.exchanges[0].tags[0].marks.of("name").column) + ")");
    EXPECT_TRUE(mentions(d[1], "has a level 'set'")) << d[1].message;
}

TEST(Validate, ATagsResultTopicCollidesWithATagNamedResultTwoLevelsBelow) {
    // acme/site/turbine1/PRESSAO/set/result: PRESSAO's write results, and the topic of tag
    // `result` of an exchange on turbine1/PRESSAO/set, which is not a child of turbine1.
    auto c = valid();
    c.exchanges.push_back(result_holder("turbine1/PRESSAO/set"));
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_TRUE(mentions(d[0], "has a level 'set'")) << d[0].message;
    EXPECT_EQ(d[1].message,
              "tag 'result' of exchange 'result_holder' uses topic "
              "'acme/site/turbine1/PRESSAO/set/result', already used by tag 'PRESSAO' of exchange "
              "'turbine1' (line " +
                  std::to_string(c.exchanges[0].tags[1].marks.of("name").line) + ", column " +
                  std::to_string(c.exchanges[0].tags[1].marks.of("name").column) + ")");
}

TEST(Validate, NestedExchangeTopicsWithoutACommonTopicAreValid) {
    // Exchanges on a topic and on its descendants claim their tags, and find no collision.
    auto c = valid();
    c.exchanges.push_back(result_holder("turbine1/area/deep"));
    c.exchanges.back().tags[0].spec.name = "PRESSAO";
    c.exchanges.push_back(result_holder("turbine1/area/deep/PRESSAO2"));
    c.exchanges.back().spec.name = "deeper";
    c.exchanges.back().spec.exchange_id = 78;
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, SameTagNameOnTwoExchangesOfOneTopic) {
    auto c = valid();
    c.exchanges[1].spec.topic = "turbine1";
    c.exchanges[1].tags.push_back(tag("PRESSAO", 8, 0, TagType::int_));
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_TRUE(mentions(d[1],
                         "tag 'PRESSAO' of exchange 'setpoints' uses topic "
                         "'acme/site/turbine1/PRESSAO', already used by tag 'PRESSAO' of "
                         "exchange 'turbine1'"))
        << d[1].message;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
