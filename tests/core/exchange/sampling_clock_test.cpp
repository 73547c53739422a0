#include "eip2mqtt/core/exchange/sampling_clock.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime mono0{1000s};
const WallTime wall0{std::chrono::sys_days{std::chrono::year{2026} / 11 / 23}.time_since_epoch()};

TEST(SamplingClock, MapsADeadlineThroughTheFirstReading) {
    SamplingClock clock;
    clock.observe(mono0, wall0);
    EXPECT_EQ(clock.to_wall(mono0 + 10ms), wall0 + 10ms);
    EXPECT_EQ(clock.to_wall(mono0 - 3ms), wall0 - 3ms);
}

TEST(SamplingClock, StepsBetweenDeadlinesAreExactWhateverTheLaterReadingsSay) {
    SamplingClock clock;
    clock.observe(mono0, wall0);
    // Later readings taken late, with the wall clock a few milliseconds off (within tolerance):
    // the anchor holds, so stamps keep whole periods.
    clock.observe(mono0 + 1s + 7ms, wall0 + 1s + 12ms);
    clock.observe(mono0 + 2s, wall0 + 2s - 15ms);
    const auto a = clock.to_wall(mono0 + 2s + 10ms);
    const auto b = clock.to_wall(mono0 + 2s + 40ms);
    EXPECT_EQ(b - a, 30ms);
    EXPECT_EQ(clock.reanchors(), 0u);
}

TEST(SamplingClock, AWallClockStepBeyondTheToleranceReanchors) {
    SamplingClock clock(20ms);
    clock.observe(mono0, wall0);
    clock.observe(mono0 + 1s, wall0 + 1s + 20ms);  // exactly the tolerance: held
    EXPECT_EQ(clock.reanchors(), 0u);
    clock.observe(mono0 + 2s, wall0 + 1h);  // stepped forward
    EXPECT_EQ(clock.reanchors(), 1u);
    EXPECT_EQ(clock.to_wall(mono0 + 2s + 5ms), wall0 + 1h + 5ms);
    clock.observe(mono0 + 3s, wall0 + 1s);  // and back
    EXPECT_EQ(clock.reanchors(), 2u);
    EXPECT_EQ(clock.to_wall(mono0 + 3s), wall0 + 1s);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
