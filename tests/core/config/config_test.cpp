#include "eip2mqtt/core/config/config.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace eip2mqtt::core::config {
namespace {

using namespace std::chrono_literals;
using plan::Direction;
using plan::TagType;

int next_line = 1;

Mark at(int line, int column = 1) { return {"c.yaml", line, column}; }

/// A tag whose every key sits on its own fresh line, so diagnostics can be located.
TagConfig tag(std::string name, std::uint16_t byte, std::uint8_t bit, TagType type) {
    TagConfig t;
    t.spec.name = std::move(name);
    t.spec.address = {byte, bit};
    t.spec.type = type;
    t.marks.node = at(next_line, 7);
    for (const char* key : {"name", "address", "type", "writable", "min", "max", "initial",
                            "deadband", "refresh_s"}) {
        t.marks.add(key, at(next_line++, 9));
    }
    return t;
}

ExchangeConfig exchange(std::string name, Direction direction, std::uint32_t id) {
    ExchangeConfig e;
    e.spec.name = name;
    e.spec.topic = name;
    e.spec.direction = direction;
    e.spec.producer_id = wire::ProducerId{0x7F000001};
    e.spec.exchange_id = id;
    e.spec.length = 16;
    e.spec.period = 100ms;
    if (direction == Direction::produce) e.spec.destination = "127.0.0.1";
    e.marks.node = at(next_line, 5);
    for (const char* key : {"name", "direction", "producer_id", "exchange_id", "length",
                            "period_ms", "timeout_ms", "source", "destination", "topic"}) {
        e.marks.add(key, at(next_line++, 5));
    }
    return e;
}

Config valid() {
    next_line = 1;
    Config c;
    c.file = "c.yaml";
    c.gateway.id = "gw";
    c.mqtt.base_topic = "acme/site";
    for (const char* key : {"url", "version", "qos", "base_topic"}) {
        c.mqtt.marks.add(key, at(next_line++, 3));
    }
    c.gateway.marks.add("id", at(next_line++, 3));
    c.gateway.marks.add("log_level", at(next_line++, 3));
    auto consumed = exchange("turbine1", Direction::consume, 2);
    consumed.tags.push_back(tag("RUNNING", 0, 0, TagType::bit));
    consumed.tags.push_back(tag("PRESSAO", 2, 0, TagType::int_));
    c.exchanges.push_back(consumed);
    auto produced = exchange("setpoints", Direction::produce, 10);
    produced.tags.push_back(tag("SPEED_SP", 0, 0, TagType::real));
    produced.tags.back().spec.writable = true;
    c.exchanges.push_back(produced);
    return c;
}

/// The one diagnostic expected; fails the test when there are none or more.
Diagnostic only(const Diagnostics& found) {
    EXPECT_EQ(found.size(), 1u);
    if (found.size() != 1) {
        for (const auto& d : found)
            ADD_FAILURE() << d.mark.line << ":" << d.mark.column << " " << d.message;
    }
    return found.empty() ? Diagnostic{} : found.front();
}

bool mentions(const Diagnostic& d, std::string_view text) {
    return d.message.find(text) != std::string::npos;
}

TEST(Marks, AddKeepsTheFirstMarkOfAKey) {
    Marks marks;
    EXPECT_TRUE(marks.add("name", at(4, 7)));
    EXPECT_TRUE(marks.add("type", at(5, 7)));
    EXPECT_FALSE(marks.add("name", at(6, 7)));  // a duplicate: the loader reports it
    EXPECT_TRUE(marks.contains("name"));
    EXPECT_FALSE(marks.contains("address"));
    EXPECT_EQ(marks.of("name").line, 4);
    EXPECT_EQ(marks.keys.size(), 2u);
}

TEST(Marks, OfFallsBackToTheNode) {
    Marks marks;
    marks.node = at(3, 5);
    marks.add("name", at(4, 7));
    EXPECT_EQ(marks.of("name").line, 4);
    EXPECT_EQ(marks.of("name").column, 7);
    EXPECT_EQ(marks.of("length").line, 3);
    EXPECT_EQ(marks.of("length").column, 5);
}

TEST(Validate, ValidConfigHasNoDiagnostics) { EXPECT_TRUE(validate(valid()).empty()); }

TEST(Validate, OverlappingTagsAreValid) {
    // As point lists name them: a word and a bit in it, a byte and its bit 0, one bit twice.
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("OVER", 3, 0, TagType::int_));  // 3..4 overlaps 2..3
    c.exchanges[0].tags.push_back(tag("BITS", 0, 0, TagType::byte));  // RUNNING is 0.0
    c.exchanges[0].tags.push_back(tag("IN_PRESSAO", 3, 4, TagType::bit));
    c.exchanges[0].tags.push_back(tag("RUNNING_AGAIN", 0, 0, TagType::bit));
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, TagPastTheExchangeLength) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("LAST", 14, 0, TagType::real));  // ends at 18 > 16
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags.back().marks.of("address").line);
    EXPECT_TRUE(mentions(d, "ends at byte 18"));
    c.exchanges[0].tags.back().spec.address.byte = 12;  // ends at 16: fits
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, WithoutLengthTagsMustEndWithin1400) {
    auto c = valid();
    c.exchanges[0].spec.length.reset();
    c.exchanges[0].tags.push_back(tag("FAR", 1396, 0, TagType::real));
    EXPECT_TRUE(validate(c).empty());
    c.exchanges[0].tags.back().spec.address.byte = 1397;
    EXPECT_TRUE(mentions(only(validate(c)), "1400"));
}

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

TEST(Validate, BitAddressOnNonBitType) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("ODD", 8, 3, TagType::word));
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags.back().marks.of("address").line);
    EXPECT_TRUE(mentions(d, "8.3"));
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

TEST(Validate, DuplicateTagNamesWithinAnExchange) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("PRESSAO", 8, 0, TagType::int_));
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags.back().marks.of("name").line);
    EXPECT_TRUE(mentions(d, "duplicate tag name 'PRESSAO'"));
    // The same name in two exchanges is fine: the topics differ.
    c = valid();
    c.exchanges[1].tags.push_back(tag("PRESSAO", 8, 0, TagType::int_));
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, WritableTagsOnConsumedExchanges) {
    auto c = valid();
    c.exchanges[0].tags[1].spec.writable = true;
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags[1].marks.of("writable").line);
}

TEST(Validate, MinAboveMax) {
    auto c = valid();
    auto& t = c.exchanges[1].tags[0];
    t.spec.mutable_extras().min = 10;
    t.spec.mutable_extras().max = 5;
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, t.marks.of("max").line);
}

TEST(Validate, MinMaxInitialOutsideTheTypeRange) {
    auto c = valid();
    auto& t = c.exchanges[0].tags[1];  // int
    t.spec.mutable_extras().min = -40000;
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, t.marks.of("min").line);
    t.spec.mutable_extras().min.reset();
    t.spec.mutable_extras().max = 32768;
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, t.marks.of("max").line);
    t.spec.mutable_extras().max = 32767;
    t.spec.mutable_extras().initial = plan::Value{std::int64_t{-32769}};
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, t.marks.of("initial").line);
    t.spec.mutable_extras().initial = plan::Value{std::int64_t{-32768}};
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, InitialOutsideMinMax) {
    auto c = valid();
    auto& t = c.exchanges[1].tags[0];
    t.spec.mutable_extras().min = 0;
    t.spec.mutable_extras().max = 4000;
    t.spec.mutable_extras().initial = plan::Value{5000.0f};
    EXPECT_TRUE(mentions(only(validate(c)), "above max 4000"));
    t.spec.mutable_extras().initial = plan::Value{3000.0f};
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
              "'acme/site/turbine1/set/result', already used by exchange 'turbine1'");

    // The other way round: the exchange's own claim is the one refused.
    c = valid();
    c.exchanges.insert(c.exchanges.begin(), result_holder("turbine1/set"));
    d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].mark.line, c.exchanges[1].marks.of("topic").line);  // turbine1's topic
    EXPECT_EQ(d[0].message,
              "exchange 'turbine1' uses topic 'acme/site/turbine1/set/result', already used by "
              "tag 'result' of exchange 'result_holder'");
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
              "'turbine1'");
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

TEST(Validate, ThirdRepeatOfATagNamePointsAtTheFirst) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("PRESSAO", 8, 0, TagType::int_));
    c.exchanges[0].tags.push_back(tag("PRESSAO", 10, 0, TagType::int_));
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    const auto first = c.exchanges[0].tags[1].marks.of("name").line;
    ASSERT_EQ(c.exchanges[0].tags[1].spec.name, "PRESSAO");
    for (const auto& diagnostic : d) {
        EXPECT_TRUE(mentions(diagnostic, "(first at c.yaml:" + std::to_string(first) + ")"))
            << diagnostic.message;
    }
}

TEST(Validate, ReservedTagNames) {
    for (const char* name : {"set", "_status", "_x", "a/b", "a+", "a#", ""}) {
        auto c = valid();
        c.exchanges[0].tags[1].spec.name = name;
        const auto d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.exchanges[0].tags[1].marks.of("name").line) << name;
    }
    auto c = valid();
    c.exchanges[0].tags[1].spec.name = "SET";  // topics are case-sensitive
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, ControlCharactersAndInvalidUtf8InTagNames) {
    for (const std::string& name :
         {std::string("A\0B", 3), std::string("A\nB"), std::string("\x1B[2J"), std::string("A\x7F"),
          std::string("\xC2\x85"), std::string("A\xFF"), std::string("\xEF\xBF\xBF")}) {
        auto c = valid();
        c.exchanges[0].tags[1].spec.name = name;
        const auto d = only(validate(c));
        EXPECT_EQ(d.mark.line, c.exchanges[0].tags[1].marks.of("name").line) << d.message;
        EXPECT_TRUE(mentions(d, "of exchange 'turbine1'")) << d.message;
    }
    auto c = valid();
    c.exchanges[0].tags[1].spec.name = std::string("A\0B", 3);
    EXPECT_EQ(only(validate(c)).message,
              "tag name 'A\\0B' contains a NUL character of exchange 'turbine1'");
    c.exchanges[0].tags[1].spec.name = "PRESS\xC3\x83O";  // UTF-8 is welcome
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, TwoTagNamesAlikeUpToANulAreBothRefused) {
    // Cut at the NUL, both would publish to turbine1/A: each is refused for its NUL.
    auto c = valid();
    c.exchanges[0].tags.push_back(tag(std::string("A\0x", 3), 8, 0, TagType::int_));
    c.exchanges[0].tags.push_back(tag(std::string("A\0y", 3), 10, 0, TagType::int_));
    const auto d = validate(c);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_TRUE(mentions(d[0], "'A\\0x' contains a NUL character")) << d[0].message;
    EXPECT_TRUE(mentions(d[1], "'A\\0y' contains a NUL character")) << d[1].message;
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
    EXPECT_TRUE(mentions(only(validate(c)), "topic 'area/t\\0' contains a NUL character"));
}

TEST(Validate, ControlCharactersAndInvalidUtf8InBaseTopicGatewayIdAndClientId) {
    auto c = valid();
    c.mqtt.base_topic = std::string("acme\0", 5);
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("base_topic").line);
    EXPECT_TRUE(mentions(d, "contains a NUL character")) << d.message;

    c = valid();
    c.gateway.id = "gw\x1B";
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.gateway.marks.of("id").line);
    EXPECT_EQ(d.message, "gateway id 'gw\\x1B' contains a control character (it is a topic level)");

    c = valid();
    c.mqtt.client_id = "client\xFF";
    c.mqtt.marks.add("client_id", at(next_line++, 3));
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("client_id").line);
    EXPECT_EQ(d.message, "client_id 'client\\xFF' is not valid UTF-8");
    c.mqtt.client_id = std::string(65536, 'c');
    EXPECT_EQ(only(validate(c)).message, "client_id is 65536 bytes long (MQTT allows 65535)");
    c.mqtt.client_id = std::string(65535, 'c');
    EXPECT_TRUE(validate(c).empty());
}

// acme/site/turbine1/{tag}/set/result: 30 bytes and the tag's name.
constexpr std::size_t longest_tag_name = 65535 - 30;

TEST(Validate, ATagWhoseResultTopicPassesMqttsLimitIsRefusedAtItsName) {
    auto c = valid();
    c.exchanges[0].tags[1].spec.name = std::string(longest_tag_name, 'P');
    EXPECT_TRUE(validate(c).empty());
    c.exchanges[0].tags[1].spec.name += 'P';
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags[1].marks.of("name").line);
    EXPECT_EQ(d.message, "tag '" + std::string(max_in_quotes_bytes, 'P') +
                             "...' (65506 bytes) of exchange 'turbine1' makes topic "
                             "'{base_topic}/{topic}/{tag}/set/result' 65536 bytes long (MQTT "
                             "allows 65535)");
}

TEST(Validate, APointListRowWhoseTopicIsTooLongIsRefusedAtItsRow) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag(std::string(longest_tag_name + 1, 'Q'), 8, 0, TagType::int_));
    c.exchanges[0].tags.back().marks = {};
    c.exchanges[0].tags.back().marks.node = {"a.csv", 7, 1};
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.file, "a.csv");
    EXPECT_EQ(d.mark.line, 7);
    EXPECT_TRUE(mentions(d, "65536 bytes long")) << d.message;
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

TEST(Validate, GatewayTopicsTooLongAreRefusedAtTheIdOrOnceAtTheBaseTopic) {
    // acme/site/_gateway/{id}/metrics: 27 bytes and the id.
    auto c = valid();
    c.gateway.id = std::string(65535 - 27, 'g');
    EXPECT_TRUE(validate(c).empty());
    c.gateway.id += 'g';
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.gateway.marks.of("id").line);
    EXPECT_TRUE(mentions(d, "topic '{base_topic}/_gateway/{gateway.id}/metrics' 65536 bytes long"))
        << d.message;
    // A base_topic leaving no room for any id: said once, not for each exchange and tag.
    c = valid();
    c.mqtt.base_topic = std::string(65535 - 18, 'b');
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("base_topic").line);
    EXPECT_TRUE(mentions(d,
                         "(65517 bytes) makes topic '{base_topic}/_gateway/{gateway.id}/metrics' "
                         "65537 bytes long"))  // with the id `gw`
        << d.message;
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

TEST(Validate, MqttSection) {
    auto c = valid();
    c.mqtt.qos = 3;
    EXPECT_EQ(only(validate(c)).mark.line, c.mqtt.marks.of("qos").line);
    c = valid();
    c.mqtt.version = 4;
    EXPECT_EQ(only(validate(c)).mark.line, c.mqtt.marks.of("version").line);
    c.mqtt.version = 3;
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, GatewaySection) {
    auto c = valid();
    c.gateway.id.clear();
    EXPECT_EQ(only(validate(c)).mark.line, c.gateway.marks.of("id").line);
    c = valid();
    c.gateway.log_level = "verbose";
    EXPECT_EQ(only(validate(c)).mark.line, c.gateway.marks.of("log_level").line);
}

TEST(Validate, NoExchanges) {
    auto c = valid();
    c.exchanges.clear();
    only(validate(c));
}

TEST(Validate, DiagnosticsComeInFileOrder) {
    auto c = valid();
    c.exchanges[1].tags[0].spec.mutable_extras().min = 5;  // later line
    c.exchanges[1].tags[0].spec.mutable_extras().max = 1;
    c.exchanges[0].spec.period = 0ms;  // earlier line
    c.gateway.id.clear();              // earliest line
    auto found = validate(c);
    ASSERT_EQ(found.size(), 3u);
    EXPECT_TRUE(std::is_sorted(found.begin(), found.end(), [](const auto& a, const auto& b) {
        return a.mark.line < b.mark.line;
    }));
    // Rows of other files (point lists) follow the configuration file's own.
    c.exchanges[0].tags.push_back(tag("PL", 16, 0, TagType::byte));  // past the end
    c.exchanges[0].tags.back().marks = {};
    c.exchanges[0].tags.back().marks.node = {"a.csv", 2, 1};
    found = validate(c);
    ASSERT_EQ(found.size(), 4u);
    EXPECT_EQ(found.back().mark.file, "a.csv");
}

TEST(MakePlans, OnePlanPerExchangeWithEveryTag) {
    const auto c = valid();
    const auto plans = make_plans(c);
    ASSERT_EQ(plans.size(), 2u);
    EXPECT_EQ(plans[0].topic, "acme/site/turbine1");
    ASSERT_EQ(plans[0].spec.tags.size(), 2u);
    EXPECT_EQ(plans[0].spec.tags[1].name, "PRESSAO");
    EXPECT_EQ(plans[0].tag_topic(plans[0].tags[1]), "acme/site/turbine1/PRESSAO");
    EXPECT_EQ(plans[0].timeout, 300ms);
    EXPECT_EQ(plans[1].tag_topic(plans[1].tags[0]), "acme/site/setpoints/SPEED_SP");
    EXPECT_EQ(plans[1].length, 16);
}

}  // namespace
}  // namespace eip2mqtt::core::config
