#include "eip2mqtt/core/throttled_log.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0{100s};

TEST(ThrottledLog, TheFirstIsLoggedThenOneSummaryPerIntervalWithItsCount) {
    ThrottledLog log(60s);
    EXPECT_EQ(log.record(t0), 1u);
    EXPECT_EQ(log.record(t0 + 1s), 0u);
    EXPECT_EQ(log.record(t0 + 59s), 0u);
    EXPECT_EQ(log.record(t0 + 60s), 3u);  // the two held back and this one
    EXPECT_EQ(log.record(t0 + 61s), 0u);  // not a "first" again: the interval holds
    EXPECT_EQ(log.record(t0 + 120s), 2u);
}

TEST(ThrottledLog, AFloodThatStopsIsSummarisedByFlushOnceTheIntervalPassed) {
    ThrottledLog log(60s);
    EXPECT_EQ(log.flush(t0), 0u);  // nothing yet
    log.record(t0);
    for (int i = 1; i <= 5; ++i) log.record(t0 + std::chrono::seconds(i));
    EXPECT_EQ(log.flush(t0 + 30s), 0u);
    EXPECT_EQ(log.flush(t0 + 60s), 5u);
    EXPECT_EQ(log.flush(t0 + 200s), 0u);  // nothing pending
    EXPECT_EQ(log.record(t0 + 200s), 1u);
}

TEST(ThrottledLog, ResetMakesTheNextOneAFirst) {
    ThrottledLog log(60s);
    log.record(t0);
    log.record(t0 + 1s);
    log.reset();
    EXPECT_EQ(log.record(t0 + 2s), 1u);
    EXPECT_EQ(log.flush(t0 + 100s), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
