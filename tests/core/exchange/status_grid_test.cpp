// StatusGrid: each exchange's periodic `_status` at its own phase of the second, so
// that exchanges started together do not all report in one tick.

#include "eip2mqtt/core/exchange/status_grid.hpp"

#include <gtest/gtest.h>

#include <set>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0 = MonoTime{} + 1000s;  // a whole second: phase 0 of the grid

TEST(StatusGrid, TheFirstReportIsDueAtOnceThenOnTheExchangesPhase) {
    StatusGrid grid;
    grid.set_phase(1, 4);  // a quarter of a second
    EXPECT_TRUE(grid.due(t0));
    grid.reported_on_grid(t0 + 3ms);
    // The first point of its grid at least a second later.
    EXPECT_EQ(grid.next(), t0 + 1250ms);
    EXPECT_FALSE(grid.due(t0 + 1249ms));
    EXPECT_TRUE(grid.due(t0 + 1250ms));
}

TEST(StatusGrid, PeriodicReportsKeepToTheGridDespiteLateTicks) {
    StatusGrid grid;
    grid.set_phase(0, 1);
    grid.reported_on_grid(t0);
    ASSERT_EQ(grid.next(), t0 + 1s);
    grid.reported_on_grid(t0 + 1s + 9ms);  // a tick 9 ms late
    EXPECT_EQ(grid.next(), t0 + 2s);
    grid.reported_on_grid(t0 + 5s + 300ms);  // after a stall of the loop: the next point only
    EXPECT_EQ(grid.next(), t0 + 6s);
}

TEST(StatusGrid, AReportOffTheGridDefersThePeriodicOneBySecondAtLeast) {
    StatusGrid grid;
    grid.set_phase(1, 2);  // half a second
    grid.reported_on_grid(t0);
    ASSERT_EQ(grid.next(), t0 + 1500ms);
    grid.reported_off_grid(t0 + 1400ms);  // a state change just before
    EXPECT_EQ(grid.next(), t0 + 2500ms);
    grid.reported_off_grid(t0 + 1500ms);  // exactly on a point: a second later
    EXPECT_EQ(grid.next(), t0 + 2500ms);
}

TEST(StatusGrid, StartedAtAnOriginTheFirstReportIsDueAtItsPhaseFromThere) {
    // Producers: their sends are spread over the period from their start, and so their status.
    StatusGrid grid;
    grid.start(t0 + 7ms, 3, 10);
    EXPECT_FALSE(grid.due(t0 + 306ms));
    EXPECT_TRUE(grid.due(t0 + 307ms));
    grid.reported_on_grid(t0 + 312ms);
    EXPECT_EQ(grid.next(), t0 + 1307ms);
    grid.reported_off_grid(t0 + 1400ms);  // stays on the same grid
    EXPECT_EQ(grid.next(), t0 + 2307ms + 1s);
}

TEST(StatusGrid, ExchangesStartedTogetherReportInDifferentTicks) {
    // 100 exchanges, each with its first report in the same tick: their next ones spread over
    // the second, one per 10 ms tick.
    std::set<MonoTime::rep> ticks;
    for (std::size_t i = 0; i < 100; ++i) {
        StatusGrid grid;
        grid.set_phase(i, 100);
        grid.reported_on_grid(t0);
        ticks.insert(
            std::chrono::duration_cast<std::chrono::milliseconds>(grid.next() - t0).count() / 10);
    }
    EXPECT_EQ(ticks.size(), 100u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
