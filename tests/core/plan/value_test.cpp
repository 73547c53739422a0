#include "eip2mqtt/core/plan/value.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

constexpr float nan_f = std::numeric_limits<float>::quiet_NaN();
constexpr double nan_d = std::numeric_limits<double>::quiet_NaN();
constexpr float inf_f = std::numeric_limits<float>::infinity();
constexpr double inf_d = std::numeric_limits<double>::infinity();

TEST(ValueJson, Bools) {
    EXPECT_EQ(to_json(Value{true}), "true");
    EXPECT_EQ(to_json(Value{false}), "false");
}

TEST(ValueJson, IntegersAreExact) {
    EXPECT_EQ(to_json(Value{std::int64_t{-2}}), "-2");
    EXPECT_EQ(to_json(Value{std::int64_t{956000}}), "956000");
    EXPECT_EQ(to_json(Value{std::numeric_limits<std::int64_t>::min()}), "-9223372036854775808");
    EXPECT_EQ(to_json(Value{std::numeric_limits<std::uint64_t>::max()}), "18446744073709551615");
    EXPECT_EQ(to_json(Value{std::uint64_t{3000000000}}), "3000000000");
}

TEST(ValueJson, AppendKeepsWhatIsThereAndWritesWhatToJsonWrites) {
    std::string out = R"({"a":)";
    append_json(out, Value{std::int64_t{-2}});
    out += ',';
    append_json(out, Value{65900.0f});
    out += ',';
    append_json(out, make_list({Value{true}, Value{nan_d}, make_text("x\"y")}));
    EXPECT_EQ(out, R"({"a":-2,65900.0,[true,"NaN","x\"y"])");
}

TEST(ValueJson, RealsPrintAsWrittenNotWidened) {
    EXPECT_EQ(to_json(Value{1.1f}), "1.1");
    EXPECT_EQ(to_json(Value{-273.15f}), "-273.15");
    EXPECT_EQ(to_json(Value{1.5f}), "1.5");
    EXPECT_EQ(to_json(Value{65900.0f}), "65900.0");
    EXPECT_EQ(to_json(Value{0.0f}), "0.0");
    EXPECT_EQ(to_json(Value{3.4028235e38f}), "3.4028235e+38");
}

TEST(ValueJson, V1IntegerBytesReadAsRealPrintShortest) {
    EXPECT_EQ(to_json(Value{std::bit_cast<float>(0x0001016Cu)}), "9.2346e-41");
}

TEST(ValueJson, LrealsRoundTripShortest) {
    EXPECT_EQ(to_json(Value{0.1}), "0.1");
    EXPECT_EQ(to_json(Value{65900.0}), "65900.0");
    EXPECT_EQ(to_json(Value{static_cast<double>(1.1f)}), "1.100000023841858");
    EXPECT_EQ(to_json(Value{1.7976931348623157e308}), "1.7976931348623157e+308");
}

TEST(ValueJson, NanAndInfinitiesAreStrings) {
    EXPECT_EQ(to_json(Value{nan_f}), "\"NaN\"");
    EXPECT_EQ(to_json(Value{nan_d}), "\"NaN\"");
    EXPECT_EQ(to_json(Value{inf_f}), "\"Infinity\"");
    EXPECT_EQ(to_json(Value{-inf_f}), "\"-Infinity\"");
    EXPECT_EQ(to_json(Value{inf_d}), "\"Infinity\"");
    EXPECT_EQ(to_json(Value{-inf_d}), "\"-Infinity\"");
}

TEST(ValueToDouble, EveryAlternative) {
    EXPECT_EQ(to_double(Value{true}), 1.0);
    EXPECT_EQ(to_double(Value{false}), 0.0);
    EXPECT_EQ(to_double(Value{std::int64_t{-100000}}), -100000.0);
    EXPECT_EQ(to_double(Value{std::uint64_t{3000000000}}), 3000000000.0);
    EXPECT_EQ(to_double(Value{1.5f}), 1.5);
    EXPECT_EQ(to_double(Value{65900.0}), 65900.0);
}

TEST(SameValue, NeedsTheSameAlternative) {
    EXPECT_TRUE(same_value(Value{std::int64_t{1}}, Value{std::int64_t{1}}));
    EXPECT_FALSE(same_value(Value{std::int64_t{1}}, Value{std::uint64_t{1}}));
    EXPECT_FALSE(same_value(Value{1.0f}, Value{1.0}));
    EXPECT_FALSE(same_value(Value{true}, Value{std::int64_t{1}}));
}

TEST(SameValue, ComparesValues) {
    EXPECT_TRUE(same_value(Value{true}, Value{true}));
    EXPECT_FALSE(same_value(Value{true}, Value{false}));
    EXPECT_FALSE(same_value(Value{1.5f}, Value{1.25f}));
    EXPECT_TRUE(same_value(Value{0.0}, Value{-0.0}));
}

TEST(SameValue, NanEqualsNan) {
    EXPECT_TRUE(same_value(Value{nan_f}, Value{nan_f}));
    EXPECT_TRUE(same_value(Value{nan_d}, Value{-nan_d}));
    EXPECT_FALSE(same_value(Value{nan_f}, Value{1.0f}));
    EXPECT_FALSE(same_value(Value{1.0}, Value{nan_d}));
    EXPECT_TRUE(same_value(Value{inf_f}, Value{inf_f}));
}

TEST(ValueJson, TextIsAnEscapedJsonString) {
    EXPECT_EQ(to_json(make_text("Batch 7")), "\"Batch 7\"");
    EXPECT_EQ(to_json(make_text("a\"b\\c")), "\"a\\\"b\\\\c\"");
    EXPECT_EQ(to_json(make_text(std::string("\n\x01\0", 3))), "\"\\n\\u0001\\u0000\"");
    EXPECT_EQ(to_json(make_text("\xC2\xB0"
                                "C")),
              "\"\xC2\xB0"
              "C\"");  // UTF-8 as it is
}

TEST(ValueJson, ListIsAJsonArrayOfItsElements) {
    EXPECT_EQ(to_json(make_list({Value{1.5f}, Value{nan_f}, Value{std::int64_t{-2}}})),
              "[1.5,\"NaN\",-2]");
    EXPECT_EQ(to_json(make_list({Value{true}, Value{false}})), "[true,false]");
}

TEST(ValueToDouble, TextAndListAreNoNumber) {
    EXPECT_TRUE(std::isnan(to_double(make_text("1"))));
    EXPECT_TRUE(std::isnan(to_double(make_list({Value{1.0}, Value{2.0}}))));
}

TEST(SameValue, TextAndListCompareContents) {
    EXPECT_TRUE(same_value(make_text("a"), make_text("a")));
    EXPECT_FALSE(same_value(make_text("a"), make_text("b")));
    EXPECT_TRUE(
        same_value(make_list({Value{nan_f}, Value{1.0f}}), make_list({Value{nan_f}, Value{1.0f}})));
    EXPECT_FALSE(same_value(make_list({Value{1.0f}}), make_list({Value{1.0f}, Value{1.0f}})));
    EXPECT_FALSE(same_value(make_list({Value{1.0f}}), make_list({Value{2.0f}})));
    EXPECT_FALSE(same_value(make_text("1"), Value{std::int64_t{1}}));
}

TEST(Value, StaysSixteenBytes) {
    // A ReportFilter per consumed tag keeps one: a text or an array is one shared pointer.
    EXPECT_EQ(sizeof(Value), 16u);
    const Value text = make_text("shared");
    const Value copy = text;  // NOLINT(performance-unnecessary-copy-initialization)
    EXPECT_EQ(&*std::get<Text>(text), &*std::get<Text>(copy));
    EXPECT_EQ(copy, make_text("shared"));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
