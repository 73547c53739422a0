#include "eip2mqtt/core/exchange/change_log.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0 = MonoTime{} + 1h;

TEST(ChangeLog, AFewChangesHaveALineEach) {
    ChangeLog log(60s);
    for (int i = 0; i < static_cast<int>(ChangeLog::burst); ++i) {
        const auto line = log.on_change(t0 + std::chrono::seconds(i));
        EXPECT_TRUE(line.single) << i;
        EXPECT_EQ(line.summary, 0u);
    }
}

TEST(ChangeLog, AStaleExchangeComingBackEveryMinuteIsLoggedLineByLine) {
    ChangeLog log(60s);
    for (int i = 0; i < 20; ++i) {
        EXPECT_TRUE(log.on_change(t0 + std::chrono::seconds(20 * i)).single) << i;
    }
}

TEST(ChangeLog, AFlappingExchangeIsSummarisedOncePerInterval) {
    // 2,000 changes, one every 10 ms: burst lines, a summary at once, then one a minute.
    ChangeLog log(60s);
    int lines = 0;
    std::uint64_t counted = 0;
    for (int i = 0; i < 2000; ++i) {
        const auto line = log.on_change(t0 + std::chrono::milliseconds(10 * i));
        if (line.single) ++lines;
        if (line.summary > 0) {
            ++lines;
            counted += line.summary;
        }
    }
    EXPECT_EQ(lines, static_cast<int>(ChangeLog::burst) + 1);
    // The rest is summarised by the tick once the interval since the summary has passed.
    EXPECT_EQ(log.flush(t0 + 59s), 0u);
    const auto rest = log.flush(t0 + 61s);
    EXPECT_EQ(counted + rest + ChangeLog::burst, 2000u);
}

TEST(ChangeLog, LinesComeBackOnceTheFlappingStoppedForAnInterval) {
    ChangeLog log(60s);
    for (int i = 0; i < 10; ++i) log.on_change(t0 + std::chrono::milliseconds(i));
    EXPECT_FALSE(log.on_change(t0 + 30s).single);  // still within a minute of the last
    EXPECT_TRUE(log.on_change(t0 + 30s + 61s).single);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
