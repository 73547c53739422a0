// validate(): each tag's name and topic, address and values.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

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

TEST(Validate, BitAddressOnNonBitType) {
    auto c = valid();
    c.exchanges[0].tags.push_back(tag("ODD", 8, 3, TagType::word));
    const auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.exchanges[0].tags.back().marks.of("address").line);
    EXPECT_TRUE(mentions(d, "8.3"));
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
              "tag name 'A\\x00B' contains a NUL character of exchange 'turbine1'");
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
    EXPECT_TRUE(mentions(d[0], "'A\\x00x' contains a NUL character")) << d[0].message;
    EXPECT_TRUE(mentions(d[1], "'A\\x00y' contains a NUL character")) << d[1].message;
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
