#include "eip2mqtt/core/exchange/arrival_stats.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime start = MonoTime{} + 1000s;

double seconds(ArrivalStats::Seconds s) { return s.count(); }

TEST(ArrivalStats, EmptyHasNoMeanNoJitterNoRate) {
    const ArrivalStats stats;
    EXPECT_EQ(stats.count(), 0u);
    EXPECT_FALSE(stats.mean_period().has_value());
    EXPECT_FALSE(stats.last_arrival().has_value());
    EXPECT_EQ(seconds(stats.jitter()), 0.0);
    EXPECT_EQ(stats.rate(start), 0.0);
}

TEST(ArrivalStats, OneArrivalHasNoMean) {
    ArrivalStats stats(100ms);
    stats.on_arrival(start);
    EXPECT_EQ(stats.count(), 1u);
    EXPECT_FALSE(stats.mean_period().has_value());
    EXPECT_EQ(stats.last_arrival(), start);
    EXPECT_EQ(seconds(stats.jitter()), 0.0);
}

TEST(ArrivalStats, RegularArrivalsHaveTheirPeriodAndNoJitter) {
    ArrivalStats stats(100ms);
    for (int i = 0; i < 50; ++i) stats.on_arrival(start + i * 100ms);
    EXPECT_EQ(stats.count(), 50u);
    ASSERT_TRUE(stats.mean_period().has_value());
    EXPECT_NEAR(seconds(*stats.mean_period()), 0.1, 1e-12);
    EXPECT_NEAR(seconds(stats.jitter()), 0.0, 1e-12);
}

TEST(ArrivalStats, JitterFollowsRfc3550AgainstTheExpectedPeriod) {
    ArrivalStats stats(100ms);
    stats.on_arrival(start);
    stats.on_arrival(start + 116ms);  // |D| = 16 ms: J = 0 + (16 - 0) / 16 = 1 ms
    EXPECT_NEAR(seconds(stats.jitter()), 0.001, 1e-12);
    stats.on_arrival(start + 200ms);  // period 84 ms, |D| = 16 ms: J = 1 + (16 - 1) / 16
    EXPECT_NEAR(seconds(stats.jitter()), 0.001 + 0.015 / 16, 1e-12);
    stats.on_arrival(start + 300ms);  // |D| = 0: J decays by 1/16
    EXPECT_NEAR(seconds(stats.jitter()), (0.001 + 0.015 / 16) * 15 / 16, 1e-12);
}

TEST(ArrivalStats, RegularButWrongRateIsJitterAgainstTheExpectedPeriod) {
    ArrivalStats stats(100ms);
    for (int i = 0; i < 200; ++i) stats.on_arrival(start + i * 150ms);
    // J converges to |150 - 100| ms.
    EXPECT_NEAR(seconds(stats.jitter()), 0.05, 1e-4);
    EXPECT_NEAR(seconds(*stats.mean_period()), 0.15, 1e-12);
}

TEST(ArrivalStats, WithoutExpectedPeriodJitterIsAgainstTheRunningMean) {
    ArrivalStats stats;
    for (int i = 0; i < 200; ++i) stats.on_arrival(start + i * 150ms);
    EXPECT_NEAR(seconds(stats.jitter()), 0.0, 1e-12);

    ArrivalStats uneven;
    uneven.on_arrival(start);
    uneven.on_arrival(start + 100ms);  // first period: no mean before it, no jitter
    EXPECT_EQ(seconds(uneven.jitter()), 0.0);
    uneven.on_arrival(start + 260ms);  // period 160 ms, mean before 100 ms: J = 60 / 16 ms
    EXPECT_NEAR(seconds(uneven.jitter()), 0.060 / 16, 1e-12);
    EXPECT_NEAR(seconds(*uneven.mean_period()), 0.130, 1e-12);
}

TEST(ArrivalStats, AlternatingPeriodsConvergeToTheirDeviation) {
    ArrivalStats stats(100ms);
    auto t = start;
    for (int i = 0; i < 400; ++i) {
        stats.on_arrival(t);
        t += i % 2 == 0 ? 90ms : 110ms;
    }
    EXPECT_NEAR(seconds(stats.jitter()), 0.010, 1e-9);
    EXPECT_NEAR(seconds(*stats.mean_period()), 0.1, 1e-3);
}

TEST(ArrivalStats, MeanIncludesGaps) {
    ArrivalStats stats(100ms);
    stats.on_arrival(start);
    stats.on_arrival(start + 100ms);
    stats.on_arrival(start + 300ms);  // one missed in between
    EXPECT_NEAR(seconds(*stats.mean_period()), 0.15, 1e-12);
}

TEST(ArrivalStats, RateCountsTheLastWindow) {
    ArrivalStats stats(std::nullopt, 1s);
    for (int i = 0; i < 20; ++i) stats.on_arrival(start + i * 100ms);  // 0 .. 1.9 s
    // (0.9 s, 1.9 s]: 10 arrivals.
    EXPECT_DOUBLE_EQ(stats.rate(start + 1900ms), 10.0);
    // (1.5 s, 2.5 s]: 1.6 .. 1.9 s, 4 arrivals.
    EXPECT_DOUBLE_EQ(stats.rate(start + 2500ms), 4.0);
    EXPECT_DOUBLE_EQ(stats.rate(start + 10s), 0.0);
}

TEST(ArrivalStats, RateIsPerSecondOfWindow) {
    ArrivalStats stats(std::nullopt, 2s);
    for (int i = 0; i < 30; ++i) stats.on_arrival(start + i * 100ms);  // 0 .. 2.9 s
    // (0.9 s, 2.9 s]: 20 arrivals in 2 s.
    EXPECT_DOUBLE_EQ(stats.rate(start + 2900ms), 10.0);
}

TEST(ArrivalStats, TimeGoingBackwardsCountsAsAZeroPeriod) {
    ArrivalStats stats;
    stats.on_arrival(start + 100ms);
    stats.on_arrival(start);
    EXPECT_EQ(stats.count(), 2u);
    EXPECT_EQ(seconds(*stats.mean_period()), 0.0);
    EXPECT_EQ(stats.last_arrival(), start + 100ms);
    EXPECT_DOUBLE_EQ(stats.rate(start + 100ms), 2.0);
}

TEST(ArrivalStats, RateStaysBoundedInMemoryAtHighRates) {
    ArrivalStats stats(std::nullopt, 1s);
    const auto n = ArrivalStats::max_window_arrivals + 1000;
    for (std::size_t i = 0; i < n; ++i) stats.on_arrival(start + i * 1us);
    const auto now = start + (n - 1) * 1us;
    // Every arrival is in the window; the kept ones span max_window_arrivals - 1 us.
    EXPECT_NEAR(stats.rate(now), 1e6, 1e6 * 1e-3);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
