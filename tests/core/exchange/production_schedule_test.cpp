#include "eip2mqtt/core/exchange/production_schedule.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime start = MonoTime{} + 1000s;

TEST(ProducerRules, FirstDeadlinesSpreadOverThePeriod) {
    EXPECT_EQ(ProductionSchedule(start, 100ms, 0, 4).deadline(), start);
    EXPECT_EQ(ProductionSchedule(start, 100ms, 1, 4).deadline(), start + 25ms);
    EXPECT_EQ(ProductionSchedule(start, 100ms, 2, 4).deadline(), start + 50ms);
    EXPECT_EQ(ProductionSchedule(start, 100ms, 3, 4).deadline(), start + 75ms);
    EXPECT_EQ(ProductionSchedule(start, 100ms, 1, 3).deadline(), start + 33333333ns);
    EXPECT_EQ(ProductionSchedule(start, 1h, 999, 1000).deadline(), start + 3596400ms);
}

TEST(ProducerRules, SingleExchangeStartsAtOnce) {
    EXPECT_EQ(ProductionSchedule(start, 100ms, 0, 1).deadline(), start);
}

TEST(ProducerRules, AdvanceAddsThePeriodToThePreviousDeadline) {
    ProductionSchedule schedule(start, 100ms, 0, 1);
    EXPECT_EQ(schedule.advance(start + 30ms), 0u);  // sent 30 ms late
    EXPECT_EQ(schedule.deadline(), start + 100ms);  // not now + period
    EXPECT_EQ(schedule.advance(start + 100ms), 0u);
    EXPECT_EQ(schedule.deadline(), start + 200ms);
}

TEST(ProducerRules, PeriodNeverDriftsUnderJitter) {
    ProductionSchedule schedule(start, 10ms, 0, 1);
    std::uint32_t seed = 12345;
    for (int i = 0; i < 1000; ++i) {
        seed = seed * 1103515245U + 12345U;  // jitter 0..9.9 ms, always less than a period
        const auto jitter = std::chrono::microseconds{seed >> 16 & 0x3FFF} % 9900;
        EXPECT_EQ(schedule.advance(schedule.deadline() + jitter), 0u);
    }
    EXPECT_EQ(schedule.deadline(), start + 1000 * 10ms);
}

TEST(ProducerRules, LateByUpToOnePeriodSkipsNothing) {
    ProductionSchedule schedule(start, 100ms, 0, 1);
    EXPECT_EQ(schedule.advance(start + 100ms), 0u);  // the next deadline is due now
    EXPECT_EQ(schedule.deadline(), start + 100ms);
}

TEST(ProducerRules, StalledLoopSkipsMissedDeadlinesKeepingThePhase) {
    ProductionSchedule schedule(start, 100ms, 1, 4);  // phase 25 ms
    // The send due at +25 ms happened at +380 ms: +125, +225 and +325 were missed.
    EXPECT_EQ(schedule.advance(start + 380ms), 3u);
    EXPECT_EQ(schedule.deadline(), start + 425ms);
    // Just over one period late: the next deadline has passed, so it is skipped.
    EXPECT_EQ(schedule.advance(start + 526ms), 1u);
    EXPECT_EQ(schedule.deadline(), start + 625ms);
    EXPECT_EQ(schedule.advance(start + 625ms), 0u);
    EXPECT_EQ(schedule.deadline(), start + 725ms);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
