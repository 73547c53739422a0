#pragma once
/// The deadlines of every produced exchange in one queue (docs/protocol.md §5), so
/// one timer drives all of them instead of one timer per exchange. Built on
/// ProductionSchedule: absolute deadlines, first sends spread over the period, missed deadlines
/// skipped and counted when a send was more than a period late.
///
/// Deadlines are batched by slots: time is cut into slots of a fixed length, aligned on the
/// clock's epoch, and an exchange is taken at the start of the slot that holds its deadline.
/// So 1,000 exchanges spread 10 us apart leave in batches rather than in 100,000 wake-ups a
/// second; a datagram leaves early by less than a slot; its next deadline is still its own
/// deadline plus the period, so its phase never drifts; and when the period is a multiple of
/// the slot (every whole-millisecond period, for a slot that divides 1 ms) the deadline falls
/// at the same place in its slot every period, so batching adds no jitter. A horizon measured
/// from the actual wake-up time would: the batch an exchange lands in would move with the
/// wake-up latency.
///
/// Pure: time is passed in. Not thread-safe.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/core/exchange/production_schedule.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class ProductionQueue {
public:
    /// Names one exchange in the queue; never reused, so a removed id stays removed.
    using Id = std::uint64_t;

    /// One exchange whose datagram is to be produced now.
    struct Due {
        Id id;
        MonoTime deadline;    ///< the deadline this datagram serves
        std::size_t skipped;  ///< deadlines skipped before the next one (the send was late)
    };

    /// `slot`: the batching grid (> 0); keep it well under the shortest period (2 ms), since an
    /// exchange is taken at most once per call.
    explicit ProductionQueue(std::chrono::nanoseconds slot);

    /// Adds an exchange with its schedule; returns its id.
    Id add(const ProductionSchedule& schedule);

    /// Removes an exchange; unknown or already removed ids are ignored.
    void remove(Id id);

    bool contains(Id id) const { return schedules_.contains(id); }
    std::size_t size() const { return schedules_.size(); }

    /// The earliest deadline; nullopt when empty.
    std::optional<MonoTime> next_deadline() const;
    /// When to call take_due() next: the start of the slot holding the earliest deadline;
    /// nullopt when empty.
    std::optional<MonoTime> next_wakeup() const;

    /// Appends to `due` every exchange whose deadline is before the end of the slot holding
    /// `now`, earliest first, and moves each to its next deadline (ProductionSchedule::advance
    /// at `now`). Each exchange appears at most once. Returns how many were appended.
    std::size_t take_due(MonoTime now, std::vector<Due>& due);

private:
    struct Entry {
        MonoTime deadline;
        Id id;
    };
    /// Pops heap entries of removed exchanges until the top is a live one.
    void drop_removed_tops();
    MonoTime slot_start(MonoTime t) const;

    std::chrono::nanoseconds slot_;
    std::unordered_map<Id, ProductionSchedule> schedules_;
    /// Min-heap on deadline. A removed exchange leaves its entry behind, dropped when it reaches
    /// the top; the top is always live, so next_deadline() needs no cleanup.
    std::vector<Entry> heap_;
    std::vector<Entry> taken_;  ///< reused by take_due()
    Id next_id_ = 1;
};

}  // namespace eip2mqtt::core::exchange
