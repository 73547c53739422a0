#include "eip2mqtt/core/plan/scaling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

constexpr double inf = std::numeric_limits<double>::infinity();

Scaling linear(ScaleRange raw, ScaleRange eu, bool clamp = false) {
    return {ScaleKind::linear, raw, eu, 1.0, 0.0, clamp, std::nullopt};
}

Scaling square_root(ScaleRange raw, ScaleRange eu, bool clamp = false) {
    return {ScaleKind::square_root, raw, eu, 1.0, 0.0, clamp, std::nullopt};
}

Scaling gain_offset(double gain, double offset) {
    return {ScaleKind::gain_offset, {}, {}, gain, offset, false, std::nullopt};
}

double eu_of(const Value& raw, const Scaling& s) { return to_double(to_engineering(raw, s).value); }

Limit limit_of(const Value& raw, const Scaling& s) { return to_engineering(raw, s).limit; }

Value i(std::int64_t v) { return Value{v}; }
Value u(std::uint64_t v) { return Value{v}; }

const Scaling level = linear({0, 32000}, {0, 100});

TEST(Scaling, LinearIsExactAtTheEndsAndBetween) {
    EXPECT_EQ(eu_of(i(0), level), 0.0);
    EXPECT_EQ(eu_of(i(32000), level), 100.0);
    EXPECT_EQ(eu_of(i(16000), level), 50.0);
    EXPECT_EQ(eu_of(i(8000), level), 25.0);
    EXPECT_EQ(limit_of(i(32000), level), Limit::none);
    // Ends that floating point would miss by one ulp: std::lerp is exact there.
    const auto odd = linear({0.1, 0.7}, {0.3, 0.9});
    EXPECT_EQ(eu_of(Value{0.7}, odd), 0.9);
    EXPECT_EQ(eu_of(Value{0.1}, odd), 0.3);
}

TEST(Scaling, LinearBeyondTheRawRangeGoesOnAndIsFlagged) {
    EXPECT_EQ(eu_of(i(-3200), level), -10.0);
    EXPECT_EQ(limit_of(i(-3200), level), Limit::low);
    EXPECT_DOUBLE_EQ(eu_of(i(32767), level), 32767.0 / 320.0);
    EXPECT_EQ(limit_of(i(32767), level), Limit::high);
}

TEST(Scaling, ClampHoldsTheEndsAndStillFlags) {
    const auto clamped = linear({0, 32000}, {0, 100}, true);
    EXPECT_EQ(eu_of(i(-3200), clamped), 0.0);
    EXPECT_EQ(limit_of(i(-3200), clamped), Limit::low);
    EXPECT_EQ(eu_of(i(32767), clamped), 100.0);
    EXPECT_EQ(limit_of(i(32767), clamped), Limit::high);
    EXPECT_EQ(limit_of(i(32000), clamped), Limit::none);
}

TEST(Scaling, AReversedRangeInvertsAndFlagsByItsEnds) {
    const auto reversed = linear({32000, 0}, {0, 100}, true);
    EXPECT_EQ(eu_of(i(32000), reversed), 0.0);
    EXPECT_EQ(eu_of(i(0), reversed), 100.0);
    EXPECT_EQ(eu_of(i(33000), reversed), 0.0);
    EXPECT_EQ(limit_of(i(33000), reversed), Limit::low);  // beyond the end that reads eu.lo
    EXPECT_EQ(limit_of(i(-1), reversed), Limit::high);
}

TEST(Scaling, SquareRootHasItsKneeAtTheRawZero) {
    const auto flow = square_root({0, 65535}, {0, 500});
    EXPECT_EQ(eu_of(u(0), flow), 0.0);
    EXPECT_EQ(eu_of(u(65535), flow), 500.0);
    EXPECT_DOUBLE_EQ(eu_of(Value{65535.0 / 4}, flow), 250.0);   // a quarter of the span: half
    EXPECT_DOUBLE_EQ(eu_of(Value{65535.0 / 100}, flow), 50.0);  // 1 %: a tenth
    const auto offset = square_root({1000, 5000}, {10, 20});
    EXPECT_EQ(eu_of(i(999), offset), 10.0);  // below the zero: eu.lo, clamped or not
    EXPECT_EQ(limit_of(i(999), offset), Limit::low);
    EXPECT_EQ(eu_of(i(-50000), offset), 10.0);
    EXPECT_EQ(eu_of(i(1000), offset), 10.0);
    EXPECT_EQ(limit_of(i(1000), offset), Limit::none);
    EXPECT_DOUBLE_EQ(eu_of(i(1000 + 4 * 4000), offset), 30.0);  // beyond hi: sqrt(4) = 2
    EXPECT_EQ(limit_of(i(17000), offset), Limit::high);
    EXPECT_EQ(eu_of(i(17000), square_root({1000, 5000}, {10, 20}, true)), 20.0);
}

TEST(Scaling, GainAndOffset) {
    const auto tenths = gain_offset(0.1, -40);
    EXPECT_DOUBLE_EQ(eu_of(i(652), tenths), 25.2);
    EXPECT_DOUBLE_EQ(eu_of(i(0), tenths), -40.0);
    EXPECT_DOUBLE_EQ(eu_of(i(-32768), tenths), -3316.8);
    EXPECT_EQ(limit_of(i(-32768), tenths), Limit::none);  // no raw range to leave
    EXPECT_EQ(eu_span(tenths), std::nullopt);
}

TEST(Scaling, NanStaysNanAndInfinitiesFollowTheLine) {
    const auto nan = Value{std::numeric_limits<float>::quiet_NaN()};
    EXPECT_TRUE(std::isnan(eu_of(nan, level)));
    EXPECT_EQ(limit_of(nan, level), Limit::none);
    EXPECT_TRUE(std::isnan(eu_of(nan, square_root({0, 1}, {0, 1}))));
    EXPECT_TRUE(std::isnan(eu_of(nan, gain_offset(2, 1))));
    // A falling range, where std::lerp of a NaN fraction gives its far end (found by fuzzing).
    auto falling = linear({-4e149, -6e153}, {-6e150, -6e153});
    falling.eu_type = TagType::byte;
    EXPECT_TRUE(std::isnan(eu_of(Value{std::numeric_limits<double>::quiet_NaN()}, falling)));
    EXPECT_EQ(limit_of(Value{std::numeric_limits<double>::quiet_NaN()}, falling), Limit::none);
    EXPECT_EQ(eu_of(Value{inf}, level), inf);
    EXPECT_EQ(limit_of(Value{inf}, level), Limit::high);
    EXPECT_EQ(eu_of(Value{-inf}, level), -inf);
    EXPECT_EQ(eu_of(Value{inf}, linear({0, 1}, {0, 100}, true)), 100.0);
    EXPECT_EQ(eu_of(Value{-inf}, linear({0, 1}, {0, 100}, true)), 0.0);
    EXPECT_EQ(eu_of(Value{-inf}, square_root({0, 1}, {0, 100})), 0.0);
    EXPECT_EQ(eu_of(Value{inf}, square_root({0, 1}, {0, 100})), inf);
}

TEST(Scaling, AnIntegerEuTypeRoundsHalfAwayFromZeroAndSaturates) {
    auto s = gain_offset(0.5, 0);
    s.eu_type = TagType::dint;
    EXPECT_EQ(to_engineering(i(5), s).value, Value{std::int64_t{3}});    // 2.5
    EXPECT_EQ(to_engineering(i(-5), s).value, Value{std::int64_t{-3}});  // -2.5
    EXPECT_EQ(to_engineering(i(3), s).value, Value{std::int64_t{2}});    // 1.5
    s.eu_type = TagType::word;
    EXPECT_EQ(to_engineering(i(200000), s).value, Value{std::uint64_t{65535}});
    EXPECT_EQ(to_engineering(i(200000), s).limit, Limit::high);
    EXPECT_EQ(to_engineering(i(-3), s).value, Value{std::uint64_t{0}});
    EXPECT_EQ(to_engineering(i(-3), s).limit, Limit::low);
    s = gain_offset(1e30, 0);
    s.eu_type = TagType::lint;
    EXPECT_EQ(to_engineering(i(1), s).value, Value{std::numeric_limits<std::int64_t>::max()});
    s.eu_type = TagType::real;
    EXPECT_EQ(to_engineering(i(3), s).value, Value{static_cast<float>(3e30)});
    EXPECT_EQ(to_engineering(i(1LL << 40), s).limit, Limit::high);
    s.eu_type = TagType::dint;  // NaN has no integer: it stays NaN, a double
    EXPECT_TRUE(std::isnan(std::get<double>(to_engineering(Value{NAN}, s).value)));
}

TEST(Scaling, EuSpanIsLowThenHigh) {
    EXPECT_EQ(eu_span(linear({0, 1}, {100, -50})), (ScaleRange{-50, 100}));
    EXPECT_EQ(eu_span(square_root({0, 1}, {0, 500})), (ScaleRange{0, 500}));
}

TEST(ScalingInverse, LinearRoundsHalfAwayFromZeroToTheWireType) {
    EXPECT_EQ(to_raw(50.0, level, TagType::int_).value(), i(16000));
    EXPECT_EQ(to_raw(100.0, level, TagType::int_).value(), i(32000));
    const auto twice = linear({0, 2}, {0, 1});
    EXPECT_EQ(to_raw(0.25, twice, TagType::int_).value(), i(1));    // raw 0.5
    EXPECT_EQ(to_raw(-0.25, twice, TagType::int_).value(), i(-1));  // raw -0.5
    EXPECT_EQ(to_raw(0.24, twice, TagType::int_).value(), i(0));    // raw 0.48
    EXPECT_EQ(to_raw(0.75, twice, TagType::int_).value(), i(2));    // raw 1.5
    EXPECT_EQ(to_raw(50.0, level, TagType::word).value(), u(16000));
    EXPECT_EQ(to_raw(50.0, level, TagType::real).value(), Value{16000.0f});
    EXPECT_EQ(to_raw(50.0, level, TagType::lreal).value(), Value{16000.0});
}

TEST(ScalingInverse, ARawFormBeyondTheWireTypeIsRefused) {
    EXPECT_EQ(to_raw(103.0, level, TagType::int_).error(), RawRefusal::out_of_range);  // 32960
    EXPECT_EQ(to_raw(-0.01, level, TagType::word).error(), RawRefusal::out_of_range);  // -3.2
    EXPECT_EQ(to_raw(1e300, gain_offset(1e-10, 0), TagType::real).error(),
              RawRefusal::out_of_range);
    EXPECT_EQ(to_raw(1e300, gain_offset(1e-10, 0), TagType::lint).error(),
              RawRefusal::out_of_range);
    EXPECT_EQ(to_raw(1e308, gain_offset(1e-10, 0), TagType::lreal).error(),
              RawRefusal::out_of_range);  // infinity
}

TEST(ScalingInverse, SquareRootSquaresAndRefusesBelowItsZero) {
    const auto flow = square_root({0, 65535}, {0, 500});
    EXPECT_EQ(to_raw(250.0, flow, TagType::word).value(), u(16384));  // 16383.75
    EXPECT_EQ(to_raw(500.0, flow, TagType::word).value(), u(65535));
    EXPECT_EQ(to_raw(0.0, flow, TagType::word).value(), u(0));
    EXPECT_EQ(to_raw(-0.1, flow, TagType::word).error(), RawRefusal::below_zero);
}

TEST(ScalingInverse, GainAndOffsetUndo) {
    const auto tenths = gain_offset(0.1, -40);
    EXPECT_EQ(to_raw(25.2, tenths, TagType::dint).value(), i(652));
    EXPECT_EQ(to_raw(-40.0, tenths, TagType::dint).value(), i(0));
    EXPECT_EQ(to_raw(150.0, tenths, TagType::dint).value(), i(1900));
}

TEST(ScalingInverse, EachKindReadsBackWhatWasWritten) {
    const Scaling kinds[] = {level, linear({-1000, 1000}, {150, -40}), gain_offset(0.1, -40),
                             square_root({100, 30000}, {0, 500})};
    for (const auto& s : kinds) {
        for (const double eu : {0.0, 12.5, 37.0, 99.9}) {
            const auto raw = to_raw(eu, s, TagType::lreal);
            ASSERT_TRUE(raw) << to_string(s.kind) << " " << eu;
            EXPECT_NEAR(eu_of(raw.value(), s), eu, 1e-9) << to_string(s.kind);
        }
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
