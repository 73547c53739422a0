#include "eip2mqtt/core/exchange/production_queue.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <vector>

namespace eip2mqtt::core::exchange {
namespace {

using namespace std::chrono_literals;
using Due = ProductionQueue::Due;

const MonoTime start = MonoTime{} + 1000s;

std::vector<ProductionQueue::Id> ids_of(const std::vector<Due>& due) {
    std::vector<ProductionQueue::Id> ids;
    for (const auto& d : due) ids.push_back(d.id);
    return ids;
}

TEST(ProductionQueue, EmptyHasNoDeadline) {
    ProductionQueue queue(0ns);
    EXPECT_FALSE(queue.next_deadline());
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 0u);
    EXPECT_TRUE(due.empty());
}

TEST(ProductionQueue, NextDeadlineIsTheEarliest) {
    ProductionQueue queue(0ns);
    queue.add(ProductionSchedule(start, 10ms, 3, 4));         // +7.5 ms
    queue.add(ProductionSchedule(start, 10ms, 1, 4));         // +2.5 ms
    queue.add(ProductionSchedule(start + 1ms, 100ms, 0, 1));  // +1 ms
    EXPECT_EQ(queue.next_deadline(), start + 1ms);
}

TEST(ProductionQueue, TakesOnlyWhatIsDueByNow) {
    ProductionQueue queue(0ns);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 4));  // start
    const auto b = queue.add(ProductionSchedule(start, 10ms, 1, 4));  // +2.5 ms
    queue.add(ProductionSchedule(start, 10ms, 2, 4));                 // +5 ms
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start + 1ms, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{a});
    EXPECT_EQ(due[0].deadline, start);
    EXPECT_EQ(due[0].skipped, 0u);
    EXPECT_EQ(queue.next_deadline(), start + 2500us);
    due.clear();
    EXPECT_EQ(queue.take_due(start + 2500us, due), 1u);  // due exactly now counts
    EXPECT_EQ(ids_of(due), std::vector{b});
}

TEST(ProductionQueue, DueSetIsEarliestFirst) {
    ProductionQueue queue(0ns);
    const auto late = queue.add(ProductionSchedule(start, 10ms, 2, 3));
    const auto early = queue.add(ProductionSchedule(start, 10ms, 0, 3));
    const auto middle = queue.add(ProductionSchedule(start, 10ms, 1, 3));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start + 9ms, due), 3u);
    EXPECT_EQ(ids_of(due), (std::vector{early, middle, late}));
}

TEST(ProductionQueue, HorizonTakesWhatIsDueSoonAndKeepsThePhase) {
    ProductionQueue queue(50us);
    // 1,000 exchanges at 10 ms: deadlines 10 us apart.
    for (std::size_t i = 0; i < 1000; ++i) queue.add(ProductionSchedule(start, 10ms, i, 1000));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 6u);  // start .. start + 50 us
    EXPECT_EQ(due.back().deadline, start + 50us);
    EXPECT_EQ(queue.next_deadline(), start + 60us);
    std::map<ProductionQueue::Id, std::vector<MonoTime>> deadlines_seen;
    for (const auto& d : due) deadlines_seen[d.id].push_back(d.deadline);
    // Wake at each announced deadline for two periods: batches of 6 (the horizon spans 6
    // deadlines), and each exchange, though taken up to 50 us early, is due again at its own
    // deadline + the period.
    while (*queue.next_deadline() < start + 20ms) {
        due.clear();
        EXPECT_EQ(queue.take_due(*queue.next_deadline(), due), 6u);
        for (const auto& d : due) deadlines_seen[d.id].push_back(d.deadline);
    }
    ASSERT_EQ(deadlines_seen.size(), 1000u);
    for (const auto& [id, times] : deadlines_seen) {
        const auto phase = std::chrono::microseconds{static_cast<std::int64_t>(id - 1) * 10};
        // Two periods, plus a third for those the last batch took early.
        ASSERT_GE(times.size(), 2u) << "exchange " << id;
        ASSERT_LE(times.size(), 3u) << "exchange " << id;
        for (int k = 0; k < static_cast<int>(times.size()); ++k) {
            EXPECT_EQ(times[static_cast<std::size_t>(k)], start + phase + k * 10ms);
        }
    }
}

TEST(ProductionQueue, EveryExchangeOncePerPeriodWithoutDrift) {
    // Wake-ups at every deadline the queue announces, each 0..40 us late: over 100 periods each
    // of 100 exchanges is taken exactly once per period, at its own phase, never drifting.
    ProductionQueue queue(50us);
    for (std::size_t i = 0; i < 100; ++i) queue.add(ProductionSchedule(start, 10ms, i, 100));
    std::map<ProductionQueue::Id, std::vector<MonoTime>> deadlines;
    std::vector<Due> due;
    std::uint32_t seed = 7;
    while (*queue.next_deadline() < start + 1s) {
        seed = seed * 1103515245U + 12345U;
        const auto now = *queue.next_deadline() + std::chrono::microseconds{(seed >> 16) % 41};
        due.clear();
        queue.take_due(now, due);
        for (const auto& d : due) {
            EXPECT_EQ(d.skipped, 0u);
            EXPECT_LE(d.deadline, now + 50us);  // early by at most the horizon
            deadlines[d.id].push_back(d.deadline);
        }
    }
    ASSERT_EQ(deadlines.size(), 100u);
    for (const auto& [id, times] : deadlines) {
        ASSERT_EQ(times.size(), 100u);
        const auto phase = std::chrono::microseconds{static_cast<std::int64_t>(id - 1) * 100};
        for (int k = 0; k < static_cast<int>(times.size()); ++k) {
            EXPECT_EQ(times[static_cast<std::size_t>(k)], start + phase + k * 10ms)
                << "exchange " << id << " period " << k;
        }
    }
}

TEST(ProductionQueue, TakesAnExchangeOncePerCallEvenWithAHorizonOverAPeriod) {
    ProductionQueue queue(25ms);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{a});
    EXPECT_EQ(queue.next_deadline(), start + 10ms);
}

TEST(ProductionQueue, LateByMoreThanAPeriodSkipsAndCounts) {
    ProductionQueue queue(0ns);
    queue.add(ProductionSchedule(start, 10ms, 1, 2));  // phase 5 ms
    std::vector<Due> due;
    // The loop stalled: the deadline at +5 ms is served at +37 ms, missing +15, +25 and +35.
    EXPECT_EQ(queue.take_due(start + 37ms, due), 1u);
    EXPECT_EQ(due[0].deadline, start + 5ms);
    EXPECT_EQ(due[0].skipped, 3u);
    EXPECT_EQ(queue.next_deadline(), start + 45ms);  // same phase, no burst
}

TEST(ProductionQueue, RemovedExchangeIsNeverTaken) {
    ProductionQueue queue(0ns);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 2));
    const auto b = queue.add(ProductionSchedule(start, 10ms, 1, 2));
    queue.remove(b);
    EXPECT_FALSE(queue.contains(b));
    EXPECT_EQ(queue.size(), 1u);
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start + 9ms, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{a});
    queue.remove(b);  // twice: ignored
    queue.remove(a);
    EXPECT_FALSE(queue.next_deadline());
}

TEST(ProductionQueue, RemovingTheEarliestMovesTheNextDeadline) {
    ProductionQueue queue(0ns);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 2));
    queue.add(ProductionSchedule(start, 10ms, 1, 2));
    queue.remove(a);
    EXPECT_EQ(queue.next_deadline(), start + 5ms);
}

TEST(ProductionQueue, AddWhileRunningJoinsAtItsOwnPhase) {
    ProductionQueue queue(0ns);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    std::vector<Due> due;
    queue.take_due(start, due);
    // Added 3 ms later (a reload): its own schedule, not the running one's.
    const auto later = start + 3ms;
    const auto b = queue.add(ProductionSchedule(later, 10ms, 0, 1));
    EXPECT_EQ(queue.next_deadline(), later);
    due.clear();
    EXPECT_EQ(queue.take_due(start + 10ms, due), 2u);
    EXPECT_EQ(ids_of(due), (std::vector{b, a}));
    EXPECT_EQ(due[0].deadline, later);
    EXPECT_EQ(due[1].deadline, start + 10ms);
}

TEST(ProductionQueue, IdsAreNeverReused) {
    ProductionQueue queue(0ns);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    queue.remove(a);
    const auto b = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    EXPECT_NE(a, b);
    EXPECT_FALSE(queue.contains(a));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{b});
}

}  // namespace
}  // namespace eip2mqtt::core::exchange
