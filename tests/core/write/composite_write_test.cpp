// Writes to arrays (whole, or one element) and to strings: the shape of the input against the
// tag's, each element's checks, and Latin-1 text no longer than the field.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "eip2mqtt/core/exchange/produced_image.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::write {
namespace EIP2MQTT_THIS_FILE {

using plan::TagType;
using plan::Value;

plan::TagSpec tag(TagType type, std::uint16_t count) {
    plan::TagSpec spec;
    spec.name = "T";
    spec.type = type;
    spec.count = count;
    spec.writable = true;
    return spec;
}

WriteInput array(std::initializer_list<ScalarInput> items) { return ArrayInput{items}; }

std::string message(const Result<Value, WriteRejection>& result) {
    return result ? "accepted" : result.error().message;
}

TEST(ArrayWrite, AllElementsAreCheckedAndConverted) {
    auto temps = tag(TagType::real, 3);
    temps.mutable_extras().max = 150;
    const auto ok = validate_write(temps, array({71.5, std::int64_t{20}, 0.25}));
    ASSERT_TRUE(ok);
    EXPECT_EQ(plan::to_json(ok.value()), "[71.5,20.0,0.25]");
    const auto high = validate_write(temps, array({71.5, 150.5, 0.25}));
    EXPECT_EQ(high.error().error, WriteError::above_max);
    EXPECT_EQ(message(high), "element 1: above max 150");
}

TEST(ArrayWrite, TheCountMustMatch) {
    const auto temps = tag(TagType::dint, 3);
    const auto short_one = validate_write(temps, array({std::int64_t{1}, std::int64_t{2}}));
    EXPECT_EQ(short_one.error().error, WriteError::wrong_type);
    EXPECT_EQ(message(short_one), R"(expected an array of 3 values or {"index": i, "value": v})");
    EXPECT_EQ(validate_write(temps, WriteInput{std::int64_t{1}}).error().error,
              WriteError::wrong_type);
    EXPECT_EQ(validate_write(temps, WriteInput{std::string("1,2,3")}).error().error,
              WriteError::wrong_type);
}

TEST(ArrayWrite, OneElementIsCheckedAsAScalarOfTheType) {
    const auto words = tag(TagType::word, 4);
    const WriteInput second = ElementInput{2, std::int64_t{7}};
    const auto ok = validate_write(words, second);
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok.value(), Value{std::uint64_t{7}});
    EXPECT_EQ(element_of(second), std::uint16_t{2});
    EXPECT_EQ(element_of(WriteInput{std::int64_t{7}}), std::nullopt);
    const auto beyond = validate_write(words, WriteInput{ElementInput{4, std::int64_t{7}}});
    EXPECT_EQ(beyond.error().error, WriteError::out_of_range);
    EXPECT_EQ(message(beyond), "index 4 beyond the 4 elements");
    EXPECT_EQ(validate_write(words, WriteInput{ElementInput{0, std::int64_t{70000}}}).error().error,
              WriteError::out_of_range);
}

TEST(ArrayWrite, AScalarTagTakesNoArrayAndNoElement) {
    const auto one = tag(TagType::dint, 1);
    EXPECT_EQ(message(validate_write(one, array({std::int64_t{1}}))),
              "expected a number or true/false, got an array");
    EXPECT_EQ(message(validate_write(one, WriteInput{ElementInput{0, std::int64_t{1}}})),
              "expected a number or true/false, got an array element");
    EXPECT_EQ(message(validate_write(one, WriteInput{std::string("1")})),
              "expected a number or true/false, got a string");
}

TEST(ArrayWrite, AnElementWriteChangesOnlyItsElement) {
    plan::ExchangePlan plan;
    plan.length = 8;
    plan.tags.push_back({tag(TagType::int_, 4)});
    exchange::ProducedImage image(plan, {}, 4);
    const auto value =
        validate_write(plan.tags[0].spec, WriteInput{ElementInput{2, std::int64_t{-1}}});
    ASSERT_TRUE(value);
    const std::vector<TagWrite> writes{TagWrite{0, value.value(), 2}};
    EXPECT_FALSE(image.holds(writes));
    ASSERT_TRUE(image.stage({1, writes}));
    std::vector<std::byte> data;
    image.project(data);
    EXPECT_EQ(plan::to_json(plan::decode_tag(data, plan.tags[0].spec)), "[0,0,-1,0]");
}

TEST(StringWrite, Latin1TextUpToTheLengthIsTaken) {
    const auto batch = tag(TagType::string, 4);
    EXPECT_EQ(validate_write(batch, WriteInput{std::string("B-17")}).value(),
              plan::make_text("B-17"));
    EXPECT_EQ(validate_write(batch, WriteInput{std::string("\xC3\xA9t\xC3\xA9")}).value(),
              plan::make_text("\xC3\xA9t\xC3\xA9"));  // 6 bytes of UTF-8, 3 of Latin-1
    EXPECT_EQ(validate_write(batch, WriteInput{std::string()}).value(), plan::make_text(""));
}

TEST(StringWrite, LongerTextOrCharactersBeyondLatin1AreRefused) {
    const auto batch = tag(TagType::string, 4);
    const auto longer = validate_write(batch, WriteInput{std::string("B-170")});
    EXPECT_EQ(longer.error().error, WriteError::out_of_range);
    EXPECT_EQ(message(longer), "longer than the tag's 4 bytes");
    const auto euro = validate_write(batch, WriteInput{std::string("5\xE2\x82\xAC")});
    EXPECT_EQ(euro.error().error, WriteError::wrong_type);
    EXPECT_EQ(message(euro), "has a character with no Latin-1 form");
    EXPECT_EQ(message(validate_write(batch, WriteInput{std::int64_t{17}})), "expected a string");
}

TEST(StringWrite, ARawWriteKeepsItsBytes) {
    const auto batch = tag(TagType::string, 4);
    const auto raw = plan::make_text(std::string("A\0\0 ", 4));
    EXPECT_EQ(validate_raw_write(batch, raw).value(), raw);
    auto words = tag(TagType::word, 2);
    words.mutable_extras().max = 10;
    const auto over = validate_raw_write(
        words, plan::make_list({Value{std::uint64_t{1}}, Value{std::uint64_t{11}}}));
    EXPECT_EQ(over.error().error, WriteError::above_max);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::write
