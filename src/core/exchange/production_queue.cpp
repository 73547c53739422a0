#include "eip2mqtt/core/exchange/production_queue.hpp"

#include <algorithm>
#include <cassert>

namespace eip2mqtt::core::exchange {
namespace {

// std::*_heap build a max-heap: "greater" puts the earliest deadline on top. Ties break on the
// id, so exchanges due at the same time leave in the order they were added.
bool later(const auto& a, const auto& b) {
    return a.deadline != b.deadline ? a.deadline > b.deadline : a.id > b.id;
}

}  // namespace

ProductionQueue::ProductionQueue(std::chrono::nanoseconds slot) : slot_(slot) {
    assert(slot > std::chrono::nanoseconds::zero());
}

MonoTime ProductionQueue::slot_start(MonoTime t) const {
    // Aligned on the clock's epoch, so that a deadline and the same deadline one period later
    // sit at the same place in their slots whenever the period is a multiple of the slot.
    return MonoTime{} +
           std::chrono::floor<std::chrono::nanoseconds>(t.time_since_epoch()) / slot_ * slot_;
}

ProductionQueue::Id ProductionQueue::add(const ProductionSchedule& schedule) {
    const Id id = next_id_++;
    schedules_.emplace(id, schedule);
    heap_.push_back({schedule.deadline(), id});
    std::push_heap(heap_.begin(), heap_.end(), later<Entry, Entry>);
    return id;
}

void ProductionQueue::remove(Id id) {
    if (schedules_.erase(id) == 0) return;
    drop_removed_tops();
}

std::optional<MonoTime> ProductionQueue::next_deadline() const {
    if (heap_.empty()) return std::nullopt;
    return heap_.front().deadline;
}

std::optional<MonoTime> ProductionQueue::next_wakeup() const {
    if (heap_.empty()) return std::nullopt;
    return slot_start(heap_.front().deadline);
}

std::size_t ProductionQueue::take_due(MonoTime now, std::vector<Due>& due) {
    const auto end = slot_start(now) + slot_;
    taken_.clear();
    while (!heap_.empty() && heap_.front().deadline < end) {
        std::pop_heap(heap_.begin(), heap_.end(), later<Entry, Entry>);
        const Entry entry = heap_.back();
        heap_.pop_back();
        const auto it = schedules_.find(entry.id);
        if (it == schedules_.end()) continue;  // removed while queued
        // §5: the next deadline is this one plus the period (never now plus the period); a
        // send more than a period late skips the deadlines it missed, keeping the phase.
        const auto skipped = it->second.advance(now);
        due.push_back({entry.id, entry.deadline, skipped});
        taken_.push_back({it->second.deadline(), entry.id});
    }
    // Pushed back only now, so that an exchange is taken at most once per call whatever the
    // slot.
    for (const auto& entry : taken_) {
        heap_.push_back(entry);
        std::push_heap(heap_.begin(), heap_.end(), later<Entry, Entry>);
    }
    drop_removed_tops();
    return taken_.size();
}

void ProductionQueue::drop_removed_tops() {
    while (!heap_.empty() && !schedules_.contains(heap_.front().id)) {
        std::pop_heap(heap_.begin(), heap_.end(), later<Entry, Entry>);
        heap_.pop_back();
    }
}

}  // namespace eip2mqtt::core::exchange
