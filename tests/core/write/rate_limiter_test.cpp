#include "eip2mqtt/core/write/rate_limiter.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::write {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
const MonoTime t0{};

TEST(RateLimiter, ZeroMeansNoLimit) {
    RateLimiter limiter(0);
    for (int i = 0; i < 1000; ++i) EXPECT_TRUE(limiter.allow(t0));
}

TEST(RateLimiter, AllowsOneSecondBurstThenTheRate) {
    RateLimiter limiter(5);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.allow(t0)) << i;
    EXPECT_FALSE(limiter.allow(t0));
    EXPECT_FALSE(limiter.allow(t0 + 100ms));  // 0.5 token
    EXPECT_TRUE(limiter.allow(t0 + 200ms));   // 1 token
    EXPECT_FALSE(limiter.allow(t0 + 200ms));
    // Refill never exceeds one second's worth.
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.allow(t0 + 10s)) << i;
    EXPECT_FALSE(limiter.allow(t0 + 10s));
}

TEST(RateLimiter, BelowOnePerSecondStillAllowsOneWrite) {
    RateLimiter limiter(0.5);
    EXPECT_TRUE(limiter.allow(t0));
    EXPECT_FALSE(limiter.allow(t0 + 1s));
    EXPECT_TRUE(limiter.allow(t0 + 2s));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::write
