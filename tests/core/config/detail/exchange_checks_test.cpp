// validate(): each exchange's name and key, its keys by direction, its topic.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Validate, LengthZeroOrOver1400) {
    auto c = valid();
    c.exchanges[0].spec.length = 0;
    c.exchanges[0].tags.clear();
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("length").line);
    c.exchanges[0].spec.length = 1401;
    d = only(validate(c));
    EXPECT_TRUE(mentions(d, "1401"));
    c.exchanges[0].spec.length = 1400;
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, NoLengthAndNoTags) {
    auto c = valid();
    c.exchanges[0].spec.length.reset();
    c.exchanges[0].tags.clear();
    EXPECT_TRUE(mentions(only(validate(c)), "needs a length"));
}

TEST(Validate, DuplicateExchangeNames) {
    auto c = valid();
    c.exchanges.push_back(exchange("turbine1", Direction::consume, 3));
    c.exchanges.back().spec.topic = "other";
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges.back().marks.of("name").line);
    EXPECT_TRUE(mentions(d, "duplicate exchange name 'turbine1'"));
}

TEST(Validate, DuplicateProducerExchangePairsPerDirection) {
    auto c = valid();
    c.exchanges.push_back(exchange("again", Direction::consume, 2));
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges.back().marks.of("exchange_id").line);
    EXPECT_TRUE(mentions(d, "'turbine1'"));

    c = valid();
    c.exchanges.push_back(exchange("again", Direction::produce, 10));
    EXPECT_TRUE(mentions(only(validate(c)), "'setpoints'"));

    // A produced and a consumed exchange may share a pair (a loopback demo).
    c = valid();
    c.exchanges.push_back(exchange("loop", Direction::produce, 2));
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, TopicsWithWildcardsOrEmptyLevels) {
    for (const char* topic : {"a/+", "#", "a/#/b", "", "/a", "a/", "a//b"}) {
        auto c = valid();
        c.exchanges[0].spec.topic = topic;
        const auto d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("topic").line) << topic;
    }
    for (const char* topic : {"acme/+/x", "a//b", "/acme", "acme/", "", "$SYS/x"}) {
        auto c = valid();
        c.mqtt.base_topic = topic;
        const auto d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.mqtt.marks.of("base_topic").line) << topic;
    }
}

TEST(Validate, ExchangeTopicLevelsStartingWithUnderscoreAreReserved) {
    auto c = valid();
    c.exchanges[0].spec.topic = "_gateway";
    only(validate(c));
    c.exchanges[0].spec.topic = "area/_x";
    only(validate(c));
}

TEST(Validate, SetLevelsInExchangeTopicsAreReserved) {
    for (const char* topic : {"set", "area/set", "set/area", "a/set/b"}) {
        auto c = valid();
        c.exchanges[0].spec.topic = topic;
        const auto d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("topic").line) << topic;
        EXPECT_EQ(d.message, "exchange 'turbine1' topic '" + std::string(topic) +
                                 "' has a level 'set', reserved for writes: the gateway takes "
                                 "{topic}/set and {topic}/{tag}/set as write requests and "
                                 "answers on their /set/result");
    }
    for (const char* topic : {"SET", "settings", "area/reset", "set_points"}) {
        auto c = valid();
        c.exchanges[0].spec.topic = topic;
        EXPECT_TRUE(validate(c).empty()) << topic;
    }
}

TEST(Validate, ControlCharactersAndInvalidUtf8InExchangeNamesAndTopics) {
    auto c = valid();
    c.exchanges[0].spec.name = "turbine\t1";
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("name").line);
    EXPECT_EQ(d.message, "exchange name 'turbine\\t1' contains a control character");
    // A topic that defaults to the name: the name's diagnostic alone.
    c.exchanges[0].spec.topic = c.exchanges[0].spec.name;
    c.exchanges[0].marks.keys.erase(
        std::find_if(c.exchanges[0].marks.keys.begin(), c.exchanges[0].marks.keys.end(),
                     [](const auto& key) { return key.first == "topic"; }));
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("name").line);

    for (const std::string& topic :
         {std::string("area/t\0", 7), std::string("area/\x01"), std::string("\xC3\x28")}) {
        c = valid();
        c.exchanges[0].spec.topic = topic;
        d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("topic").line) << d.message;
    }
    c = valid();
    c.exchanges[0].spec.topic = std::string("area/t\0", 7);
    EXPECT_TRUE(mentions(only(validate(c)), "topic 'area/t\\x00' contains a NUL character"));
    // A right-to-left override: "area/<RLO>tes/1t" reads "area/t1/set"; shown escaped.
    c = valid();
    c.exchanges[0].spec.topic = "area/\xE2\x80\xAEtes/1t";
    EXPECT_TRUE(mentions(only(validate(c)),
                         "topic 'area/\\u202Etes/1t' contains a bidirectional control character"));
}

TEST(Validate, AnExchangeTopicTooLongIsRefusedOnceNotForEachTag) {
    // acme/site/{topic}/set/result: 21 bytes and the topic.
    auto c = valid();
    c.exchanges[0].spec.topic = std::string(65535 - 21, 't');
    c.exchanges[0].tags.clear();
    EXPECT_TRUE(validate(c).empty());
    c.exchanges[0].spec.topic += 't';
    c.exchanges[0].tags = valid().exchanges[0].tags;
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("topic").line);
    EXPECT_TRUE(mentions(d, "topic '{base_topic}/{topic}/set/result' 65536 bytes long"))
        << d.message;
    // A topic that defaults to the name: at the name.
    c.exchanges[0].spec.name = c.exchanges[0].spec.topic;
    c.exchanges[0].marks.keys.erase(
        std::find_if(c.exchanges[0].marks.keys.begin(), c.exchanges[0].marks.keys.end(),
                     [](const auto& key) { return key.first == "topic"; }));
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].marks.of("name").line);
}

TEST(Validate, PeriodRange) {
    for (auto period : {0ms, 1ms, 3600001ms}) {
        auto c = valid();
        c.exchanges[0].spec.period = period;
        EXPECT_EQ(only(validate(c)).mark.line, c.exchanges[0].marks.of("period_ms").line);
    }
    for (auto period : {2ms, 3600000ms}) {
        auto c = valid();
        c.exchanges[0].spec.period = period;
        EXPECT_TRUE(validate(c).empty());
    }
}

TEST(Validate, DestinationOnlyOnProducedExchanges) {
    auto c = valid();
    c.exchanges[1].spec.destination.clear();
    EXPECT_TRUE(mentions(only(validate(c)), "no destination"));
    c = valid();
    c.exchanges[0].spec.destination = "10.0.0.1";
    EXPECT_EQ(only(validate(c)).mark.line, c.exchanges[0].marks.of("destination").line);
}

TEST(Validate, TimeoutAndSourceOnlyOnConsumedExchanges) {
    auto c = valid();
    c.exchanges[1].spec.timeout = 300ms;
    EXPECT_EQ(only(validate(c)).mark.line, c.exchanges[1].marks.of("timeout_ms").line);
    c = valid();
    c.exchanges[1].spec.source = 0x7F000001;
    EXPECT_EQ(only(validate(c)).mark.line, c.exchanges[1].marks.of("source").line);
}

TEST(Validate, NoExchanges) {
    auto c = valid();
    c.exchanges.clear();
    only(validate(c));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
