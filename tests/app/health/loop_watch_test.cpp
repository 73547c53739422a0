// The loop's watch: a tick far later than asked is a hold, logged once, then summarised at
// most once a minute with the longest.

#include "eip2mqtt/app/health/loop_watch.hpp"

#include <gtest/gtest.h>

#include "tests/support/fakes/log_capture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

TEST(LoopWatch, ATickLateByTenTicksIsAHoldLoggedOnceThenSummarisedAMinuteLater) {
    test::LogCapture log;
    LoopWatch watch;
    const core::MonoTime t0{100s};
    EXPECT_EQ(watch.on_tick(t0, t0 + 99ms), 99ms);
    EXPECT_EQ(watch.holds(), 0u);
    EXPECT_TRUE(log.lines().empty());

    EXPECT_EQ(watch.on_tick(t0 + 1s, t0 + 1s + 1625ms), 1625ms);
    auto lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("loop: held 1625 ms"), std::string::npos) << lines[0];

    watch.on_tick(t0 + 5s, t0 + 5s + 300ms);
    watch.on_tick(t0 + 6s, t0 + 6s + 800ms);
    watch.flush(t0 + 30s);
    EXPECT_TRUE(log.lines().empty());
    watch.flush(t0 + 64s);
    lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("held 2 more time(s), the longest 800 ms"), std::string::npos)
        << lines[0];
    EXPECT_EQ(watch.holds(), 3u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
