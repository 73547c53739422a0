#include "eip2mqtt/core/command/source_limiter.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr MonoTime t0 = MonoTime{} + 1h;

TEST(SourceLimiter, OneSourceSpendsOnlyItsOwnBucket) {
    SourceLimiter limiter(5);
    int flooder = 0;
    for (int i = 0; i < 100; ++i) flooder += limiter.allow(1, t0) ? 1 : 0;
    EXPECT_EQ(flooder, 5);
    // Another source is untouched by the first's flood.
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.allow(2, t0)) << i;
    EXPECT_FALSE(limiter.allow(2, t0));
    // Tokens come back at the rate: 200 ms at 5/s is one.
    EXPECT_TRUE(limiter.allow(1, t0 + 200ms));
    EXPECT_FALSE(limiter.allow(1, t0 + 200ms));
}

TEST(SourceLimiter, TheTableOfSourcesIsBounded) {
    SourceLimiter limiter(1, 16);
    for (std::uint32_t source = 0; source < 1000; ++source) limiter.allow(source, t0);
    EXPECT_LE(limiter.sources(), 16u);
}

TEST(SourceLimiter, ZeroMeansNoLimit) {
    SourceLimiter limiter(0);
    for (int i = 0; i < 1000; ++i) EXPECT_TRUE(limiter.allow(1, t0));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
