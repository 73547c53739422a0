#pragma once
/// The deadlines of every produced exchange in one queue (eip-protocol.md §5; issue #6), so
/// one timer drives all of them instead of one timer per exchange. Built on
/// ProductionSchedule: absolute deadlines, first sends spread over the period, missed deadlines
/// skipped and counted when a send was more than a period late.
///
/// take_due() also takes the exchanges due within a small horizon after `now`, so that 1,000
/// exchanges spread 10 us apart leave in batches rather than in 100,000 wake-ups a second. A
/// datagram taken that way leaves early by at most the horizon; its next deadline is still its
/// own deadline plus the period, so the phase of each exchange never drifts.
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

    /// `horizon`: how far ahead of `now` take_due() reaches; keep it well under the shortest
    /// period (2 ms), since an exchange is taken at most once per call.
    explicit ProductionQueue(std::chrono::nanoseconds horizon);

    /// Adds an exchange with its schedule; returns its id.
    Id add(const ProductionSchedule& schedule);

    /// Removes an exchange; unknown or already removed ids are ignored.
    void remove(Id id);

    bool contains(Id id) const { return schedules_.contains(id); }
    std::size_t size() const { return schedules_.size(); }

    /// The earliest deadline, when the next call to take_due() has work; nullopt when empty.
    std::optional<MonoTime> next_deadline() const;

    /// Appends to `due` every exchange whose deadline is at or before `now + horizon`, earliest
    /// first, and moves each to its next deadline (ProductionSchedule::advance at `now`). Each
    /// exchange appears at most once. Returns how many were appended.
    std::size_t take_due(MonoTime now, std::vector<Due>& due);

private:
    struct Entry {
        MonoTime deadline;
        Id id;
    };
    /// Pops heap entries of removed exchanges until the top is a live one.
    void drop_removed_tops();

    std::chrono::nanoseconds horizon_;
    std::unordered_map<Id, ProductionSchedule> schedules_;
    /// Min-heap on deadline. A removed exchange leaves its entry behind, dropped when it reaches
    /// the top; the top is always live, so next_deadline() needs no cleanup.
    std::vector<Entry> heap_;
    std::vector<Entry> taken_;  ///< reused by take_due()
    Id next_id_ = 1;
};

}  // namespace eip2mqtt::core::exchange
