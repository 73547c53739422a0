// The chaos schedule (tests/support/chaos_schedule.hpp): the same seed gives the same faults,
// they come one at a time with quiet between, and the run is bounded.

#include "tests/support/chaos_schedule.hpp"

#include <gtest/gtest.h>

#include <set>

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

TEST(ChaosSchedule, TheSameSeedGivesTheSameFaults) {
    const auto a = chaos_schedule(7, 60s, 1000ms);
    const auto b = chaos_schedule(7, 60s, 1000ms);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].str(), b[i].str());
    const auto c = chaos_schedule(8, 60s, 1000ms);
    EXPECT_FALSE(a.size() == c.size() && a[0].str() == c[0].str());
}

TEST(ChaosSchedule, FaultsComeOneAtATimeWithQuietBetweenAndEndInTime) {
    std::set<ChaosKind> kinds;
    for (std::uint64_t seed = 1; seed <= 50; ++seed) {
        const auto schedule = chaos_schedule(seed, 30s, 1000ms);
        ASSERT_FALSE(schedule.empty());
        EXPECT_LE(schedule.size(), 11u);
        for (std::size_t i = 0; i < schedule.size(); ++i) {
            const auto& f = schedule[i];
            kinds.insert(f.kind);
            EXPECT_LE(f.at + f.length, 30s) << f.str();
            EXPECT_LE(f.length, 3000ms) << f.str();
            EXPECT_LT(f.delay, 125ms) << f.str();  // within the lease's assumptions
            if (i > 0) {
                const auto& before = schedule[i - 1];
                EXPECT_GE(f.at - (before.at + before.length), 3000ms) << f.str();
            }
        }
    }
    EXPECT_EQ(kinds.size(), chaos_kinds) << "50 seeds draw every kind of fault";
}

}  // namespace
}  // namespace eip2mqtt::test
