// Writes to scaled tags: in engineering units, limits in those units, made raw by the inverse
// of the tag's scale; and the command port's raw writes against the same limits.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::write {
namespace EIP2MQTT_THIS_FILE {

using plan::ScaleKind;
using plan::Scaling;
using plan::TagType;
using plan::Value;

plan::TagSpec scaled(TagType type, Scaling scale, std::optional<double> min = std::nullopt,
                     std::optional<double> max = std::nullopt) {
    plan::TagSpec spec;
    spec.name = "T";
    spec.type = type;
    spec.writable = true;
    spec.mutable_extras().scale = scale;
    spec.mutable_extras().min = min;
    spec.mutable_extras().max = max;
    return spec;
}

const Scaling oil{ScaleKind::gain_offset, {}, {}, 0.1, -40, false, std::nullopt};
const Scaling level{ScaleKind::linear, {0, 32000}, {0, 100}, 1, 0, true, std::nullopt};
const Scaling flow{ScaleKind::square_root, {0, 65535}, {0, 500}, 1, 0, false, std::nullopt};

Value i(std::int64_t v) { return Value{v}; }

TEST(ScaledWrite, EngineeringValuesBecomeRaw) {
    EXPECT_EQ(validate_write(scaled(TagType::dint, oil), WriteInput{25.2}).value(), i(652));
    EXPECT_EQ(validate_write(scaled(TagType::dint, oil), WriteInput{std::int64_t{-40}}).value(),
              i(0));
    EXPECT_EQ(validate_write(scaled(TagType::int_, level), WriteInput{std::int64_t{50}}).value(),
              i(16000));
    EXPECT_EQ(validate_write(scaled(TagType::word, flow), WriteInput{250.0}).value(),
              Value{std::uint64_t{16384}});
    EXPECT_EQ(validate_write(scaled(TagType::real, level), WriteInput{12.5}).value(),
              Value{4000.0f});
}

TEST(ScaledWrite, LimitsAreEngineeringValues) {
    const auto tag = scaled(TagType::dint, oil, -40, 150);
    EXPECT_TRUE(validate_write(tag, WriteInput{150.0}));
    const auto above = validate_write(tag, WriteInput{150.5});
    ASSERT_FALSE(above);
    EXPECT_EQ(above.error().error, WriteError::above_max);
    EXPECT_EQ(above.error().message, "above max 150");
    EXPECT_EQ(validate_write(tag, WriteInput{std::int64_t{-41}}).error().error,
              WriteError::below_min);
}

TEST(ScaledWrite, NoRawFormIsRefusedWithTheReason) {
    const auto high = validate_write(scaled(TagType::int_, level), WriteInput{103.0});  // 32960
    ASSERT_FALSE(high);
    EXPECT_EQ(high.error().error, WriteError::out_of_range);
    EXPECT_EQ(high.error().message, "raw value out of range for int (-32768..32767)");
    const auto root = validate_write(scaled(TagType::word, flow), WriteInput{-1.0});
    ASSERT_FALSE(root);
    EXPECT_EQ(root.error().error, WriteError::out_of_range);
    EXPECT_NE(root.error().message.find("square root's zero"), std::string::npos);
}

TEST(ScaledWrite, TypesAndFinitenessAreCheckedFirst) {
    EXPECT_EQ(validate_write(scaled(TagType::dint, oil), WriteInput{true}).error().error,
              WriteError::wrong_type);
    EXPECT_EQ(validate_write(scaled(TagType::dint, oil),
                             WriteInput{std::numeric_limits<double>::infinity()})
                  .error()
                  .error,
              WriteError::not_finite);
    auto read_only = scaled(TagType::dint, oil);
    read_only.writable = false;
    EXPECT_EQ(validate_write(read_only, WriteInput{1.0}).error().error, WriteError::read_only);
}

TEST(ScaledWrite, RawWritesMeetTheEngineeringLimits) {
    const auto tag = scaled(TagType::dint, oil, -40, 150);
    EXPECT_EQ(validate_raw_write(tag, i(1900)).value(), i(1900));  // 150 degC
    EXPECT_EQ(validate_raw_write(tag, i(1901)).error().error, WriteError::above_max);
    EXPECT_EQ(validate_raw_write(tag, i(-1)).error().error, WriteError::below_min);
    EXPECT_EQ(validate_raw_write(scaled(TagType::real, level),
                                 Value{std::numeric_limits<float>::quiet_NaN()})
                  .error()
                  .error,
              WriteError::not_finite);
}

TEST(ScaledWrite, RawWritesOfUnscaledTagsAreAsBefore) {
    plan::TagSpec tag;
    tag.type = TagType::int_;
    tag.writable = true;
    tag.mutable_extras().max = 100;
    EXPECT_EQ(validate_raw_write(tag, i(100)).value(), i(100));
    EXPECT_EQ(validate_raw_write(tag, i(101)).error().error, WriteError::above_max);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::write
