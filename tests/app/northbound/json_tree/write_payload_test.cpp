#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <variant>

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::write::WriteError;
using core::write::WriteInput;

WriteInput accepted(std::string_view payload) {
    const auto result = parse_tag_write(payload);
    EXPECT_TRUE(result.ok()) << payload << ": " << (result.ok() ? "" : result.error().message);
    return result.ok() ? result.value() : WriteInput{false};
}

WriteError rejected(std::string_view payload) {
    const auto result = parse_tag_write(payload);
    EXPECT_FALSE(result.ok()) << payload;
    return result.ok() ? WriteError::empty : result.error().error;
}

WriteError exchange_rejected(std::string_view payload) {
    const auto result = parse_exchange_write(payload);
    EXPECT_FALSE(result.ok()) << payload;
    return result.ok() ? WriteError::retained : result.error().error;
}

TEST(ParseTagWrite, AcceptsUnsignedInteger) {
    EXPECT_EQ(accepted("42"), WriteInput{std::uint64_t{42}});
    EXPECT_EQ(accepted("0"), WriteInput{std::uint64_t{0}});
    EXPECT_EQ(accepted(" 42\n"), WriteInput{std::uint64_t{42}});
}

TEST(ParseTagWrite, AcceptsNegativeInteger) {
    EXPECT_EQ(accepted("-2"), WriteInput{std::int64_t{-2}});
    EXPECT_EQ(accepted("-9223372036854775808"),
              WriteInput{std::numeric_limits<std::int64_t>::min()});
}

TEST(ParseTagWrite, KeepsTheLargestUnsignedExact) {
    EXPECT_EQ(accepted("18446744073709551615"),
              WriteInput{std::numeric_limits<std::uint64_t>::max()});
}

TEST(ParseTagWrite, AcceptsReal) {
    EXPECT_EQ(accepted("12.5"), WriteInput{12.5});
    EXPECT_EQ(accepted("-0.25"), WriteInput{-0.25});
    // Beyond u64 an integer can only be a double; validation finds it out of range.
    EXPECT_TRUE(std::holds_alternative<double>(accepted("18446744073709551616")));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("-9223372036854775809")));
}

TEST(ParseTagWrite, IntegersAreExactHoweverTheyAreSpelt) {
    EXPECT_EQ(accepted("1e3"), WriteInput{std::uint64_t{1000}});
    EXPECT_EQ(accepted("12.0"), WriteInput{std::uint64_t{12}});
    EXPECT_EQ(accepted("-2.50e1"), WriteInput{std::int64_t{-25}});
    EXPECT_EQ(accepted("0.0"), WriteInput{std::uint64_t{0}});
    EXPECT_EQ(accepted("-0.0"), WriteInput{std::uint64_t{0}});
    EXPECT_EQ(accepted("9007199254740993.0"), WriteInput{std::uint64_t{9007199254740993}});
    EXPECT_EQ(accepted("-9223372036854775808.0"),
              WriteInput{std::numeric_limits<std::int64_t>::min()});
    EXPECT_EQ(accepted("1.8446744073709551615e19"),
              WriteInput{std::numeric_limits<std::uint64_t>::max()});
    EXPECT_EQ(accepted("100e-2"), WriteInput{std::uint64_t{1}});
}

TEST(ParseTagWrite, FractionsStayDoublesEvenWhenTheyRoundToIntegers) {
    // 2^53 + 0.5 is 2^53 as a double: the text, not the double, says it is no integer.
    EXPECT_TRUE(std::holds_alternative<double>(accepted("9007199254740992.5")));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("1.0000000000000000001")));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("1e-400")));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("1.8446744073709551616e19")));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("1e25")));
}

TEST(ParseTagWrite, AcceptsBooleans) {
    EXPECT_EQ(accepted("true"), WriteInput{true});
    EXPECT_EQ(accepted("false"), WriteInput{false});
}

TEST(ParseTagWrite, AcceptsValueObject) {
    EXPECT_EQ(accepted(R"({"value":42})"), WriteInput{std::uint64_t{42}});
    EXPECT_EQ(accepted(R"({ "value" : -7 })"), WriteInput{std::int64_t{-7}});
    EXPECT_EQ(accepted(R"({"value":true})"), WriteInput{true});
    EXPECT_EQ(accepted(R"({"value":3.5})"), WriteInput{3.5});
}

TEST(ParseTagWrite, EmptyIsMalformed) {
    EXPECT_EQ(rejected(""), WriteError::malformed);
    EXPECT_EQ(rejected("   "), WriteError::malformed);
    EXPECT_EQ(parse_tag_write("").error().message, "malformed JSON");
}

TEST(ParseTagWrite, StringsAreTextForAStringTag) {
    // Whether the tag takes a text is validation's to say: "expected a number..." otherwise.
    EXPECT_EQ(accepted(R"("")"), WriteInput{std::string()});
    EXPECT_EQ(accepted(R"("42")"), WriteInput{std::string("42")});
    EXPECT_EQ(accepted(R"({"value":"B-é"})"), WriteInput{std::string("B-\xC3\xA9")});
}

TEST(ParseTagWrite, ArraysOfScalarsAreAnArrayTagsElements) {
    using core::write::ArrayInput;
    EXPECT_EQ(accepted("[]"), WriteInput{ArrayInput{}});
    const ArrayInput four{{std::uint64_t{42}, std::int64_t{-1}, 2.5, true}};
    EXPECT_EQ(accepted("[42, -1, 2.5, true]"), WriteInput{four});
    EXPECT_EQ(accepted(R"({"value":[1.0]})"), WriteInput{ArrayInput{{std::uint64_t{1}}}});
    EXPECT_EQ(rejected("[[1]]"), WriteError::malformed);
    EXPECT_EQ(rejected(R"([{"value":1}])"), WriteError::malformed);
    EXPECT_EQ(rejected("[1,]"), WriteError::malformed);
    EXPECT_EQ(rejected(R"([1, "a"])"), WriteError::wrong_type);
    EXPECT_EQ(parse_tag_write("[1, null]").error().message,
              "element 1: expected a number or true/false, got null");
}

TEST(ParseTagWrite, AnIndexAndAValueAreOneElement) {
    using core::write::ElementInput;
    const ElementInput second{2, 71.5};
    const ElementInput first{0, true};
    EXPECT_EQ(accepted(R"({"index": 2, "value": 71.5})"), WriteInput{second});
    EXPECT_EQ(accepted(R"({"value": true, "index": 0})"), WriteInput{first});
    EXPECT_EQ(rejected(R"({"index": -1, "value": 1})"), WriteError::wrong_type);
    EXPECT_EQ(rejected(R"({"index": 1.5, "value": 1})"), WriteError::wrong_type);
    EXPECT_EQ(rejected(R"({"index": 65536, "value": 1})"), WriteError::wrong_type);
    EXPECT_EQ(rejected(R"({"index": 1, "value": [1]})"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"index": 1, "value": "a"})"), WriteError::wrong_type);
    EXPECT_EQ(rejected(R"({"index": 1})"), WriteError::malformed);
}

TEST(ParseTagWrite, NullIsWrongType) {
    EXPECT_EQ(rejected("null"), WriteError::wrong_type);
    EXPECT_EQ(rejected(R"({"value":null})"), WriteError::wrong_type);
}

TEST(ParseTagWrite, GarbageIsMalformed) {
    for (const auto* payload : {"garbage", "4 2", "42 x", "42,", "tru", "0x10", "+1", "01", ".5",
                                "{", "}", "{\"value\":}", "{value:1}", "'1'"}) {
        EXPECT_EQ(rejected(payload), WriteError::malformed) << payload;
    }
}

TEST(ParseTagWrite, NonFiniteIsMalformed) {
    for (const auto* payload :
         {"NaN", "nan", "Infinity", "-Infinity", "1e999", "-1e999", "{\"value\":1e999}"}) {
        EXPECT_EQ(rejected(payload), WriteError::malformed) << payload;
    }
}

TEST(ParseTagWrite, ObjectsOtherThanValueAreMalformed) {
    EXPECT_EQ(rejected("{}"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"x":2})"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"value":1,"x":2})"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"Value":1})"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"value":{"value":1}})"), WriteError::malformed);
    EXPECT_EQ(rejected(R"({"value":1,"value":2})"), WriteError::malformed);
    EXPECT_EQ(parse_tag_write(R"({"value":1,"x":2})").error().message,
              R"(expected a JSON scalar, an array, {"value": ...} or {"index": i, "value": ...})");
}

TEST(ParseTagWrite, DeepNestingIsMalformed) {
    const std::string closed = std::string(10000, '[') + "1" + std::string(10000, ']');
    EXPECT_EQ(rejected(closed), WriteError::malformed);
    EXPECT_EQ(rejected(std::string(10000, '[')), WriteError::malformed);
    std::string objects;
    for (int i = 0; i < 10000; ++i) objects += R"({"value":)";
    objects += "1" + std::string(10000, '}');
    EXPECT_EQ(rejected(objects), WriteError::malformed);
}

TEST(ParseTagWrite, InvalidUtf8IsMalformed) {
    EXPECT_EQ(rejected("\"\xff\xfe\""), WriteError::malformed);
    EXPECT_EQ(rejected("{\"val\xc3\x28\":1}"), WriteError::malformed);
    EXPECT_EQ(rejected("4\xff"), WriteError::malformed);
    EXPECT_EQ(rejected(std::string_view("4\0", 2)), WriteError::malformed);
    EXPECT_EQ(rejected(std::string_view("42\0junk", 7)), WriteError::malformed);
}

TEST(ParseTagWrite, PayloadOverTheLimitIsTooLargeAndSaysSo) {
    const std::string spaces = std::string(1024 * 1024, ' ') + "42";
    EXPECT_EQ(rejected(spaces), WriteError::too_large);
    EXPECT_EQ(parse_tag_write(spaces).error().message,
              "payload too large (1048578 bytes, limit 262144)");
    const std::string digits(1024 * 1024, '7');
    EXPECT_EQ(rejected(digits), WriteError::too_large);
    const std::string text = "\"" + std::string(1024 * 1024, 'a') + "\"";
    EXPECT_EQ(rejected(text), WriteError::too_large);
    EXPECT_EQ(exchange_rejected("{" + std::string(300 * 1024, ' ') + "}"), WriteError::too_large);
    // At the limit it is parsed (and here found to be a number).
    EXPECT_EQ(accepted(std::string(256 * 1024 - 2, ' ') + "42"), WriteInput{std::uint64_t{42}});
}

TEST(ParseTagWrite, AHugeDigitStringWithinTheLimitIsADouble) {
    // Far beyond 64 bits: a double, which validation then finds out of range.
    EXPECT_TRUE(std::holds_alternative<double>(accepted(std::string(300, '7'))));
    EXPECT_TRUE(std::holds_alternative<double>(accepted("7." + std::string(100000, '0') + "1")));
    EXPECT_EQ(accepted("7." + std::string(100000, '0')), WriteInput{std::uint64_t{7}});
    EXPECT_EQ(accepted("7e-99999999999999999999"), WriteInput{0.0});
}

TEST(ParseExchangeWrite, AcceptsMixedFormsInPayloadOrder) {
    const auto result =
        parse_exchange_write(R"({"SPEED_SP":3100.5,"START":true,"COUNT":{"value":7},"OFFSET":-3,)"
                             R"("BIG":18446744073709551615,"STOP":{"value":false}})");
    ASSERT_TRUE(result.ok()) << result.error().message;
    const auto& writes = result.value();
    ASSERT_EQ(writes.size(), 6u);
    EXPECT_EQ(writes[0].first, "SPEED_SP");
    EXPECT_EQ(writes[0].second, WriteInput{3100.5});
    EXPECT_EQ(writes[1].first, "START");
    EXPECT_EQ(writes[1].second, WriteInput{true});
    EXPECT_EQ(writes[2].first, "COUNT");
    EXPECT_EQ(writes[2].second, WriteInput{std::uint64_t{7}});
    EXPECT_EQ(writes[3].first, "OFFSET");
    EXPECT_EQ(writes[3].second, WriteInput{std::int64_t{-3}});
    EXPECT_EQ(writes[4].first, "BIG");
    EXPECT_EQ(writes[4].second, WriteInput{std::numeric_limits<std::uint64_t>::max()});
    EXPECT_EQ(writes[5].first, "STOP");
    EXPECT_EQ(writes[5].second, WriteInput{false});
}

TEST(ParseExchangeWrite, EmptyObjectIsEmpty) {
    EXPECT_EQ(exchange_rejected("{}"), WriteError::empty);
}

TEST(ParseExchangeWrite, NonObjectIsMalformed) {
    for (const auto* payload : {"", "42", "true", "[]", R"(["A",1])", "null", R"("A")", "garbage",
                                R"({"A":1} x)", "{\"A\":1"}) {
        EXPECT_EQ(exchange_rejected(payload), WriteError::malformed) << payload;
    }
}

TEST(ParseExchangeWrite, DuplicateKeysAreMalformed) {
    EXPECT_EQ(exchange_rejected(R"({"A":1,"B":2,"A":3})"), WriteError::malformed);
    EXPECT_EQ(exchange_rejected(R"({"A":{"value":1,"value":2}})"), WriteError::malformed);
}

TEST(ParseExchangeWrite, OneBadValueFailsTheWholeWrite) {
    const auto result = parse_exchange_write(R"({"A":1,"B":[2,null]})");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().error, WriteError::wrong_type);
    EXPECT_EQ(result.error().message, "B: element 1: expected a number or true/false, got null");
    EXPECT_EQ(exchange_rejected(R"({"A":1,"B":[[2]]})"), WriteError::malformed);
    EXPECT_EQ(exchange_rejected(R"({"A":1,"B":{"value":2,"x":1}})"), WriteError::malformed);
    EXPECT_EQ(exchange_rejected(R"({"A":1,"B":{"value":{"value":2}}})"), WriteError::malformed);
    EXPECT_EQ(exchange_rejected(R"({"A":1,"B":null})"), WriteError::wrong_type);
    EXPECT_EQ(exchange_rejected(R"({"A":1e999})"), WriteError::malformed);
}

TEST(ParseExchangeWrite, HostileInputIsMalformed) {
    std::string deep = R"({"A":)" + std::string(10000, '[') + std::string(10000, ']') + "}";
    EXPECT_EQ(exchange_rejected(deep), WriteError::malformed);
    std::string objects;
    for (int i = 0; i < 10000; ++i) objects += R"({"A":)";
    objects += "1" + std::string(10000, '}');
    EXPECT_EQ(exchange_rejected(objects), WriteError::malformed);
    EXPECT_EQ(exchange_rejected("{\"\xff\":1}"), WriteError::malformed);

    std::string big = "{";
    for (int i = 0; big.size() < 1024 * 1024; ++i) big += "\"T" + std::to_string(i) + "\":1,";
    big += "\"END\":1}";
    EXPECT_EQ(exchange_rejected(big), WriteError::too_large);
}

// Parsing and validation together, as the gateway runs them: lint writes are exact.
core::Result<core::plan::Value, core::write::WriteRejection> write_lint(std::string_view payload) {
    core::plan::TagSpec spec;
    spec.name = "L";
    spec.type = core::plan::TagType::lint;
    spec.writable = true;
    const auto input = parse_tag_write(payload);
    EXPECT_TRUE(input.ok()) << payload;
    return core::write::validate_write(spec, input.value());
}

TEST(WriteToLint, IntegersAreExactAndNothingElsePasses) {
    EXPECT_EQ(write_lint("9007199254740993.0").value(),
              core::plan::Value{std::int64_t{9007199254740993}});
    EXPECT_EQ(write_lint("-9223372036854775808").value(),
              core::plan::Value{std::numeric_limits<std::int64_t>::min()});
    EXPECT_EQ(write_lint("-9223372036854775809").error().error, WriteError::out_of_range);
    EXPECT_EQ(write_lint("9223372036854775808").error().error, WriteError::out_of_range);
    EXPECT_EQ(write_lint("9007199254740992.5").error().error, WriteError::not_integer);
    EXPECT_EQ(write_lint("0.5").error().error, WriteError::not_integer);
    EXPECT_EQ(write_lint("1e300").error().error, WriteError::out_of_range);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
