#include "eip2mqtt/core/exchange/production_queue.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <vector>

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using Due = ProductionQueue::Due;

const MonoTime start = MonoTime{} + 1000s;

std::vector<ProductionQueue::Id> ids_of(const std::vector<Due>& due) {
    std::vector<ProductionQueue::Id> ids;
    for (const auto& d : due) ids.push_back(d.id);
    return ids;
}

TEST(ProductionQueue, EmptyHasNoDeadline) {
    ProductionQueue queue(1ns);  // no batching
    EXPECT_FALSE(queue.next_deadline());
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 0u);
    EXPECT_TRUE(due.empty());
}

TEST(ProductionQueue, NextDeadlineIsTheEarliest) {
    ProductionQueue queue(1ns);                               // no batching
    queue.add(ProductionSchedule(start, 10ms, 3, 4));         // +7.5 ms
    queue.add(ProductionSchedule(start, 10ms, 1, 4));         // +2.5 ms
    queue.add(ProductionSchedule(start + 1ms, 100ms, 0, 1));  // +1 ms
    EXPECT_EQ(queue.next_deadline(), start + 1ms);
}

TEST(ProductionQueue, TakesOnlyWhatIsDueByNow) {
    ProductionQueue queue(1ns);                                       // no batching
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
    ProductionQueue queue(1ns);  // no batching
    const auto late = queue.add(ProductionSchedule(start, 10ms, 2, 3));
    const auto early = queue.add(ProductionSchedule(start, 10ms, 0, 3));
    const auto middle = queue.add(ProductionSchedule(start, 10ms, 1, 3));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start + 9ms, due), 3u);
    EXPECT_EQ(ids_of(due), (std::vector{early, middle, late}));
}

TEST(ProductionQueue, SlotBatchesWhatIsDueInItAndKeepsThePhase) {
    ProductionQueue queue(50us);
    // 1,000 exchanges at 10 ms: deadlines 10 us apart, 5 to a slot.
    for (std::size_t i = 0; i < 1000; ++i) queue.add(ProductionSchedule(start, 10ms, i, 1000));
    std::vector<Due> due;
    EXPECT_EQ(queue.next_wakeup(), start);
    EXPECT_EQ(queue.take_due(start, due), 5u);  // start .. start + 40 us
    EXPECT_EQ(due.back().deadline, start + 40us);
    EXPECT_EQ(queue.next_deadline(), start + 50us);
    std::map<ProductionQueue::Id, std::vector<MonoTime>> deadlines_seen;
    for (const auto& d : due) deadlines_seen[d.id].push_back(d.deadline);
    // Wake at each announced slot for two periods: each exchange, though taken up to 40 us
    // early, is due again at its own deadline + the period.
    while (*queue.next_wakeup() < start + 20ms) {
        due.clear();
        EXPECT_EQ(queue.take_due(*queue.next_wakeup(), due), 5u);
        for (const auto& d : due) deadlines_seen[d.id].push_back(d.deadline);
    }
    ASSERT_EQ(deadlines_seen.size(), 1000u);
    for (const auto& [id, times] : deadlines_seen) {
        const auto phase = std::chrono::microseconds{static_cast<std::int64_t>(id - 1) * 10};
        ASSERT_EQ(times.size(), 2u) << "exchange " << id;
        EXPECT_EQ(times[0], start + phase);
        EXPECT_EQ(times[1], start + phase + 10ms);
    }
}

TEST(ProductionQueue, WakeUpIsTheStartOfTheSlotOfTheEarliestDeadline) {
    ProductionQueue queue(250us);
    queue.add(ProductionSchedule(start + 1730us, 10ms, 0, 1));
    EXPECT_EQ(queue.next_deadline(), start + 1730us);
    EXPECT_EQ(queue.next_wakeup(), start + 1500us);  // early by less than a slot
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start + 1499us, due), 0u);  // the slot before
    EXPECT_EQ(queue.take_due(start + 1500us, due), 1u);
}

TEST(ProductionQueue, LateWakeUpTakesTheLateAndTheRestOfItsSlotOnly) {
    ProductionQueue queue(250us);
    queue.add(ProductionSchedule(start, 10ms, 0, 40));  // deadlines 250 us apart
    queue.add(ProductionSchedule(start, 10ms, 1, 40));
    queue.add(ProductionSchedule(start, 10ms, 2, 40));
    queue.add(ProductionSchedule(start, 10ms, 3, 40));
    std::vector<Due> due;
    // Woken 300 us late, in the second slot: the first two, not the third (next slot).
    EXPECT_EQ(queue.take_due(start + 300us, due), 2u);
    EXPECT_EQ(due[1].deadline, start + 250us);
    EXPECT_EQ(queue.next_wakeup(), start + 500us);
}

TEST(ProductionQueue, BatchingAddsNoJitterWhenThePeriodIsAMultipleOfTheSlot) {
    // Whatever the wake-up latency (under a slot), each exchange is taken at the start of the
    // same slot every period: a constant offset from its deadline, so no jitter from batching.
    ProductionQueue queue(250us);
    for (std::size_t i = 0; i < 7; ++i) queue.add(ProductionSchedule(start, 10ms, i, 7));
    std::map<ProductionQueue::Id, std::vector<std::chrono::nanoseconds>> offsets;
    std::vector<Due> due;
    std::uint32_t seed = 99;
    while (*queue.next_wakeup() < start + 1s) {
        seed = seed * 1103515245U + 12345U;
        const auto now = *queue.next_wakeup() + std::chrono::microseconds{(seed >> 16) % 200};
        due.clear();
        queue.take_due(now, due);
        const auto slot = now - (now - start) % 250us;  // the slot this batch was taken in
        for (const auto& d : due) offsets[d.id].push_back(slot - d.deadline);
    }
    ASSERT_EQ(offsets.size(), 7u);
    for (const auto& [id, offset] : offsets) {
        ASSERT_EQ(offset.size(), 100u);
        for (const auto o : offset) EXPECT_EQ(o, offset.front()) << "exchange " << id;
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
    while (*queue.next_wakeup() < start + 1s) {
        seed = seed * 1103515245U + 12345U;
        const auto now = *queue.next_wakeup() + std::chrono::microseconds{(seed >> 16) % 41};
        due.clear();
        queue.take_due(now, due);
        for (const auto& d : due) {
            EXPECT_EQ(d.skipped, 0u);
            EXPECT_LT(d.deadline, now + 50us);  // early by less than a slot
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

TEST(ProductionQueue, TakesAnExchangeOncePerCallEvenWithASlotOverAPeriod) {
    ProductionQueue queue(25ms);
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{a});
    EXPECT_EQ(queue.next_deadline(), start + 10ms);
}

TEST(ProductionQueue, LateByMoreThanAPeriodSkipsAndCounts) {
    ProductionQueue queue(1ns);                        // no batching
    queue.add(ProductionSchedule(start, 10ms, 1, 2));  // phase 5 ms
    std::vector<Due> due;
    // The loop stalled: the deadline at +5 ms is served at +37 ms, missing +15, +25 and +35.
    EXPECT_EQ(queue.take_due(start + 37ms, due), 1u);
    EXPECT_EQ(due[0].deadline, start + 5ms);
    EXPECT_EQ(due[0].skipped, 3u);
    EXPECT_EQ(queue.next_deadline(), start + 45ms);  // same phase, no burst
}

TEST(ProductionQueue, RemovedExchangeIsNeverTaken) {
    ProductionQueue queue(1ns);  // no batching
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
    ProductionQueue queue(1ns);  // no batching
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 2));
    queue.add(ProductionSchedule(start, 10ms, 1, 2));
    queue.remove(a);
    EXPECT_EQ(queue.next_deadline(), start + 5ms);
}

TEST(ProductionQueue, AddWhileRunningJoinsAtItsOwnPhase) {
    ProductionQueue queue(1ns);  // no batching
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
    ProductionQueue queue(1ns);  // no batching
    const auto a = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    queue.remove(a);
    const auto b = queue.add(ProductionSchedule(start, 10ms, 0, 1));
    EXPECT_NE(a, b);
    EXPECT_FALSE(queue.contains(a));
    std::vector<Due> due;
    EXPECT_EQ(queue.take_due(start, due), 1u);
    EXPECT_EQ(ids_of(due), std::vector{b});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
