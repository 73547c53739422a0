#include "eip2mqtt/core/write/write_validation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>

namespace eip2mqtt::core::write {
namespace EIP2MQTT_THIS_FILE {

using plan::TagType;
using plan::Value;

constexpr auto i64_min = std::numeric_limits<std::int64_t>::min();
constexpr auto i64_max = std::numeric_limits<std::int64_t>::max();
constexpr auto u64_max = std::numeric_limits<std::uint64_t>::max();

plan::TagSpec tag(TagType type, std::optional<double> min = std::nullopt,
                  std::optional<double> max = std::nullopt) {
    plan::TagSpec spec;
    spec.name = "T";
    spec.type = type;
    spec.writable = true;
    spec.mutable_extras().min = min;
    spec.mutable_extras().max = max;
    return spec;
}

/// The accepted value, or a failure naming the rejection.
Value accepted(const plan::TagSpec& spec, const WriteInput& input) {
    const auto result = validate_write(spec, input);
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
    return result.ok() ? *result : Value{false};
}

WriteRejection rejected(const plan::TagSpec& spec, const WriteInput& input) {
    const auto result = validate_write(spec, input);
    EXPECT_FALSE(result.ok());
    return result.ok() ? WriteRejection{WriteError::malformed, "accepted"} : result.error();
}

WriteError error_of(const plan::TagSpec& spec, const WriteInput& input) {
    return rejected(spec, input).error;
}

TEST(WriteError, NamesAreSnakeCaseAndDistinct) {
    EXPECT_EQ(to_string(WriteError::malformed), "malformed");
    EXPECT_EQ(to_string(WriteError::unknown_tag), "unknown_tag");
    EXPECT_EQ(to_string(WriteError::read_only), "read_only");
    EXPECT_EQ(to_string(WriteError::wrong_type), "wrong_type");
    EXPECT_EQ(to_string(WriteError::not_integer), "not_integer");
    EXPECT_EQ(to_string(WriteError::below_min), "below_min");
    EXPECT_EQ(to_string(WriteError::above_max), "above_max");
    EXPECT_EQ(to_string(WriteError::out_of_range), "out_of_range");
    EXPECT_EQ(to_string(WriteError::not_finite), "not_finite");
    EXPECT_EQ(to_string(WriteError::retained), "retained");
    EXPECT_EQ(to_string(WriteError::expired), "expired");
    EXPECT_EQ(to_string(WriteError::queue_full), "queue_full");
    EXPECT_EQ(to_string(WriteError::empty), "empty");
    EXPECT_EQ(to_string(WriteError::rate_limited), "rate_limited");
    EXPECT_EQ(to_string(WriteError::bad_response_topic), "bad_response_topic");
    EXPECT_EQ(to_string(WriteError::overlapping_tags), "overlapping_tags");
    EXPECT_EQ(to_string(WriteError::too_large), "too_large");
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < write_error_count; ++i) {
        names.insert(to_string(static_cast<WriteError>(i)));
    }
    EXPECT_EQ(names.size(), write_error_count);
}

TEST(ValidateWrite, ReadOnlyTagIsRejected) {
    auto spec = tag(TagType::int_);
    spec.writable = false;
    const auto rejection = rejected(spec, std::int64_t{1});
    EXPECT_EQ(rejection.error, WriteError::read_only);
    EXPECT_EQ(rejection.message, "tag is read-only");
}

TEST(ValidateWrite, BitTakesTrueFalseZeroAndOne) {
    const auto spec = tag(TagType::bit);
    EXPECT_EQ(accepted(spec, true), Value{true});
    EXPECT_EQ(accepted(spec, false), Value{false});
    EXPECT_EQ(accepted(spec, std::int64_t{1}), Value{true});
    EXPECT_EQ(accepted(spec, std::int64_t{0}), Value{false});
    EXPECT_EQ(accepted(spec, std::uint64_t{1}), Value{true});
    EXPECT_EQ(accepted(spec, std::uint64_t{0}), Value{false});
}

TEST(ValidateWrite, BitRejectsOtherNumbers) {
    const auto spec = tag(TagType::bit);
    const auto two = rejected(spec, std::int64_t{2});
    EXPECT_EQ(two.error, WriteError::out_of_range);
    EXPECT_EQ(two.message, "out of range for bit (0..1)");
    EXPECT_EQ(error_of(spec, std::int64_t{-1}), WriteError::out_of_range);
    EXPECT_EQ(error_of(spec, std::uint64_t{2}), WriteError::out_of_range);
    const auto real = rejected(spec, 1.0);
    EXPECT_EQ(real.error, WriteError::wrong_type);
    EXPECT_EQ(real.message, "expected true or false");
}

TEST(ValidateWrite, BoolForANumericTagIsWrongType) {
    for (const auto type : {TagType::byte, TagType::int_, TagType::word, TagType::dint,
                            TagType::udint, TagType::lint, TagType::real, TagType::lreal}) {
        const auto rejection = rejected(tag(type), true);
        EXPECT_EQ(rejection.error, WriteError::wrong_type) << plan::to_string(type);
        EXPECT_EQ(rejection.message, "expected a number");
    }
}

TEST(ValidateWrite, FractionalNumberForAnIntegerTagIsNotInteger) {
    const auto rejection = rejected(tag(TagType::int_), 12.5);
    EXPECT_EQ(rejection.error, WriteError::not_integer);
    EXPECT_EQ(rejection.message, "expected an integer");
    EXPECT_EQ(error_of(tag(TagType::lint), -0.5), WriteError::not_integer);
}

TEST(ValidateWrite, DoubleForAnIntegerTagIsAFractionOrBeyondItsRange) {
    // WriteInput: integers of 64 bits come as int64/uint64 however they were spelt, so a
    // double that happens to be whole is a fraction that rounded (2^53 + 0.5) or lies beyond
    // 64 bits (-2^63 - 1 rounds to -2^63).
    EXPECT_EQ(error_of(tag(TagType::int_), 12.0), WriteError::not_integer);
    EXPECT_EQ(error_of(tag(TagType::lint), 9007199254740992.0), WriteError::not_integer);
    EXPECT_EQ(error_of(tag(TagType::lint), -9223372036854775808.0), WriteError::out_of_range);
    EXPECT_EQ(error_of(tag(TagType::lint), 1e30), WriteError::out_of_range);
    EXPECT_EQ(error_of(tag(TagType::lint), -1e30), WriteError::out_of_range);
    EXPECT_EQ(error_of(tag(TagType::udint), 18446744073709551616.0), WriteError::out_of_range);
}

TEST(ValidateWrite, NonFiniteNumbersAreRejected) {
    for (const auto type : {TagType::int_, TagType::real, TagType::lreal, TagType::bit}) {
        for (const double d : {std::nan(""), std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()}) {
            const auto rejection = rejected(tag(type), d);
            EXPECT_EQ(rejection.error, WriteError::not_finite) << plan::to_string(type);
            EXPECT_EQ(rejection.message, "not a finite number");
        }
    }
}

TEST(ValidateWrite, ByteRangeEdges) {
    const auto spec = tag(TagType::byte);
    EXPECT_EQ(accepted(spec, std::int64_t{0}), Value{std::uint64_t{0}});
    EXPECT_EQ(accepted(spec, std::uint64_t{255}), Value{std::uint64_t{255}});
    EXPECT_EQ(rejected(spec, std::int64_t{256}).message, "out of range for byte (0..255)");
    EXPECT_EQ(error_of(spec, std::int64_t{-1}), WriteError::out_of_range);
}

TEST(ValidateWrite, IntRangeEdges) {
    const auto spec = tag(TagType::int_);
    EXPECT_EQ(accepted(spec, std::int64_t{-32768}), Value{std::int64_t{-32768}});
    EXPECT_EQ(accepted(spec, std::int64_t{32767}), Value{std::int64_t{32767}});
    EXPECT_EQ(accepted(spec, std::uint64_t{32767}), Value{std::int64_t{32767}});
    const auto low = rejected(spec, std::int64_t{-32769});
    EXPECT_EQ(low.error, WriteError::out_of_range);
    EXPECT_EQ(low.message, "out of range for int (-32768..32767)");
    EXPECT_EQ(error_of(spec, std::int64_t{32768}), WriteError::out_of_range);
    EXPECT_EQ(error_of(spec, std::uint64_t{32768}), WriteError::out_of_range);
    EXPECT_EQ(error_of(spec, std::int64_t{70000}), WriteError::out_of_range);
}

TEST(ValidateWrite, WordRangeEdges) {
    const auto spec = tag(TagType::word);
    EXPECT_EQ(accepted(spec, std::int64_t{65535}), Value{std::uint64_t{65535}});
    EXPECT_EQ(accepted(spec, std::int64_t{0}), Value{std::uint64_t{0}});
    const auto high = rejected(spec, std::int64_t{65536});
    EXPECT_EQ(high.error, WriteError::out_of_range);
    EXPECT_EQ(high.message, "out of range for word (0..65535)");
    EXPECT_EQ(error_of(spec, std::int64_t{-1}), WriteError::out_of_range);
}

TEST(ValidateWrite, DintRangeEdges) {
    const auto spec = tag(TagType::dint);
    EXPECT_EQ(accepted(spec, std::int64_t{-2147483648}), Value{std::int64_t{-2147483648}});
    EXPECT_EQ(accepted(spec, std::int64_t{2147483647}), Value{std::int64_t{2147483647}});
    EXPECT_EQ(error_of(spec, std::int64_t{-2147483649}), WriteError::out_of_range);
    EXPECT_EQ(error_of(spec, std::int64_t{2147483648}), WriteError::out_of_range);
}

TEST(ValidateWrite, UdintRangeEdges) {
    const auto spec = tag(TagType::udint);
    EXPECT_EQ(accepted(spec, std::int64_t{4294967295}), Value{std::uint64_t{4294967295}});
    EXPECT_EQ(accepted(spec, std::uint64_t{4294967295}), Value{std::uint64_t{4294967295}});
    const auto high = rejected(spec, std::int64_t{4294967296});
    EXPECT_EQ(high.error, WriteError::out_of_range);
    EXPECT_EQ(high.message, "out of range for udint (0..4294967295)");
    EXPECT_EQ(error_of(spec, std::int64_t{-1}), WriteError::out_of_range);
}

TEST(ValidateWrite, LintRangeEdgesAreExact) {
    const auto spec = tag(TagType::lint);
    EXPECT_EQ(accepted(spec, i64_max), Value{i64_max});
    EXPECT_EQ(accepted(spec, i64_min), Value{i64_min});
    EXPECT_EQ(accepted(spec, std::uint64_t{i64_max}), Value{i64_max});
    const auto high = rejected(spec, std::uint64_t{i64_max} + 1);
    EXPECT_EQ(high.error, WriteError::out_of_range);
    EXPECT_EQ(high.message, "out of range for lint (-9223372036854775808..9223372036854775807)");
    EXPECT_EQ(error_of(spec, u64_max), WriteError::out_of_range);
    // 2^63 is the double nearest int64 max, and one past it.
    EXPECT_EQ(error_of(spec, 9223372036854775808.0), WriteError::out_of_range);
}

TEST(ValidateWrite, RealTakesNumbersWithinFloatRange) {
    const auto spec = tag(TagType::real);
    EXPECT_EQ(accepted(spec, 1.5), Value{1.5F});
    EXPECT_EQ(accepted(spec, std::int64_t{-3}), Value{-3.0F});
    EXPECT_EQ(accepted(spec, u64_max), Value{static_cast<float>(u64_max)});
    const double max = std::numeric_limits<float>::max();
    EXPECT_EQ(accepted(spec, max), Value{std::numeric_limits<float>::max()});
    EXPECT_EQ(accepted(spec, -max), Value{-std::numeric_limits<float>::max()});
    const auto high = rejected(spec, 3.5e38);
    EXPECT_EQ(high.error, WriteError::out_of_range);
    EXPECT_EQ(high.message, "out of range for real (-3.4028235e+38..3.4028235e+38)");
    EXPECT_EQ(error_of(spec, -3.5e38), WriteError::out_of_range);
}

TEST(ValidateWrite, LrealTakesAnyFiniteNumber) {
    const auto spec = tag(TagType::lreal);
    EXPECT_EQ(accepted(spec, 1e300), Value{1e300});
    EXPECT_EQ(accepted(spec, -std::numeric_limits<double>::max()),
              Value{-std::numeric_limits<double>::max()});
    EXPECT_EQ(accepted(spec, std::int64_t{-7}), Value{-7.0});
}

TEST(ValidateWrite, MinAndMaxPrintAsTheYamlWroteThem) {
    const auto spec = tag(TagType::real, 0.0, 4000.0);
    EXPECT_EQ(accepted(spec, 4000.0), Value{4000.0F});
    EXPECT_EQ(accepted(spec, std::int64_t{0}), Value{0.0F});
    const auto high = rejected(spec, 4000.5);
    EXPECT_EQ(high.error, WriteError::above_max);
    EXPECT_EQ(high.message, "above max 4000");
    const auto low = rejected(spec, -0.1);
    EXPECT_EQ(low.error, WriteError::below_min);
    EXPECT_EQ(low.message, "below min 0");
    EXPECT_EQ(rejected(tag(TagType::lreal, 0.5), 0.25).message, "below min 0.5");
}

TEST(ValidateWrite, RealLimitsAreCheckedAgainstTheInputNotItsFloatRounding) {
    // 4000.0001 rounds to 4000.0f, but the client asked for more than the max.
    EXPECT_EQ(error_of(tag(TagType::real, std::nullopt, 4000.0), 4000.0001), WriteError::above_max);
}

TEST(ValidateWrite, IntegerLimitsWithFractionsRoundInward) {
    const auto spec = tag(TagType::int_, -1.5, 10.5);
    EXPECT_EQ(accepted(spec, std::int64_t{-1}), Value{std::int64_t{-1}});
    EXPECT_EQ(accepted(spec, std::int64_t{10}), Value{std::int64_t{10}});
    EXPECT_EQ(error_of(spec, std::int64_t{-2}), WriteError::below_min);
    EXPECT_EQ(error_of(spec, std::int64_t{11}), WriteError::above_max);
}

TEST(ValidateWrite, LintLimitsAreComparedExactly) {
    // 2^53 + 1 becomes 2^53 as a double: a double comparison would let it through.
    const double limit = 9007199254740992.0;  // 2^53
    const auto spec = tag(TagType::lint, -limit, limit);
    EXPECT_EQ(accepted(spec, std::int64_t{9007199254740992}),
              Value{std::int64_t{9007199254740992}});
    EXPECT_EQ(error_of(spec, std::int64_t{9007199254740993}), WriteError::above_max);
    EXPECT_EQ(error_of(spec, std::int64_t{-9007199254740993}), WriteError::below_min);
    // A max beyond int64 never rejects; a min at -2^63 accepts int64 min.
    const auto wide = tag(TagType::lint, -9223372036854775808.0, 1e30);
    EXPECT_EQ(accepted(wide, i64_max), Value{i64_max});
    EXPECT_EQ(accepted(wide, i64_min), Value{i64_min});
}

TEST(ValidateWrite, TypeChecksComeBeforeLimits) {
    const auto spec = tag(TagType::int_, 0.0, 100.0);
    EXPECT_EQ(error_of(spec, 150.5), WriteError::not_integer);
    EXPECT_EQ(error_of(spec, std::int64_t{40000}), WriteError::out_of_range);
    EXPECT_EQ(error_of(spec, true), WriteError::wrong_type);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::write
