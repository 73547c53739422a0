// The loop's tick: each tick's times come from the injected clock, and the whole-second scan is
// flagged once per second of that clock, however many ticks ran meanwhile.

#include "eip2mqtt/app/health/tick_timer.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <vector>

#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// Runs ticks until `ticks` ran, advancing the clock by `step` in each; the times seen.
std::vector<TickTimes> run_ticks(test::FakeClock& clock, std::size_t ticks,
                                 std::chrono::milliseconds step) {
    boost::asio::io_context loop;
    TickTimer timer(loop.get_executor(), clock);
    std::vector<TickTimes> seen;
    timer.start(clock.monotonic(), [&](const TickTimes& times) {
        seen.push_back(times);
        clock.advance(step);
        if (seen.size() == ticks) timer.cancel();
    });
    loop.run_for(30s);  // bounded: the last tick cancels the timer and the loop runs dry
    return seen;
}

TEST(TickTimer, EachTickCarriesTheClocksTimes) {
    test::FakeClock clock(core::WallTime{} + 1000h);
    const auto start = clock.monotonic();
    const auto seen = run_ticks(clock, 3, 7ms);
    ASSERT_EQ(seen.size(), 3u);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i].now, start + i * 7ms);
        EXPECT_EQ(seen[i].wall, core::WallTime{} + 1000h + i * 7ms);
    }
}

TEST(TickTimer, TheScanIsFlaggedOncePerSecondOfTheClock) {
    test::FakeClock clock;
    // 250 ms of the clock per tick: seconds end on ticks 4, 8 and 12 (counted from 0).
    const auto seen = run_ticks(clock, 13, 250ms);
    ASSERT_EQ(seen.size(), 13u);
    std::vector<std::size_t> scans;
    for (std::size_t i = 0; i < seen.size(); ++i) {
        if (seen[i].refresh_scan) scans.push_back(i);
    }
    EXPECT_EQ(scans, (std::vector<std::size_t>{4, 8, 12}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
