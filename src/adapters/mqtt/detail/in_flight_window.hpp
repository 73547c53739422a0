#pragma once
/// The publications handed to Paho and not yet completed, by id. Ids are given in order, and
/// Paho completes them nearly in order (QoS 0 as written, QoS 1 as acknowledged), so a ring
/// indexed by `id - first id` finds one in O(1) and completed ones leave from the front (a
/// Ring, not a std::deque, which allocates a block every few publications). A
/// completion for an id no longer here (abandoned on a connection loss, or never given) is
/// ignored, so nothing is counted twice.
///
/// It also counts the pending items that await the broker's acknowledgement (QoS >= 1): the
/// broker's Receive Maximum bounds those alone (MQTT 5 §3.3.4), QoS 0 are done once written.
///
/// Module-private (src/adapters/mqtt/detail); not thread-safe: the Sender guards it.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>

#include "eip2mqtt/core/ring.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

template <class T>
class InFlightWindow {
public:
    /// Registers `item`, which awaits an acknowledgement when `acknowledged` (QoS >= 1);
    /// returns its id (1, 2, ...).
    std::uint64_t add(T item, bool acknowledged) {
        entries_.push_back({std::move(item), false, acknowledged});
        ++pending_;
        if (acknowledged) ++pending_acknowledged_;
        return next_id_++;
    }

    /// Takes the item of a pending id out of the window; nullopt when unknown or done.
    std::optional<T> complete(std::uint64_t id) {
        if (id < first_id_ || id >= next_id_) return std::nullopt;
        Entry& entry = entries_[static_cast<std::size_t>(id - first_id_)];
        if (entry.done) return std::nullopt;
        entry.done = true;
        --pending_;
        if (entry.acknowledged) --pending_acknowledged_;
        std::optional<T> item(std::move(entry.item));
        while (!entries_.empty() && entries_.front().done) {
            entries_.pop_front();
            ++first_id_;
        }
        return item;
    }

    /// Hands every pending item to `f(id, T&&)` in id order and forgets them all.
    template <class F>
    void abandon_all(F&& f) {
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            if (!entries_[i].done) f(first_id_ + i, std::move(entries_[i].item));
        }
        entries_.clear();
        first_id_ = next_id_;
        pending_ = 0;
        pending_acknowledged_ = 0;
    }

    std::size_t pending() const { return pending_; }
    /// The pending items added with `acknowledged`.
    std::size_t pending_acknowledged() const { return pending_acknowledged_; }
    bool empty() const { return pending_ == 0; }

private:
    struct Entry {
        T item{};
        bool done = false;
        bool acknowledged = false;
    };
    core::Ring<Entry> entries_;
    std::uint64_t first_id_ = 1;  ///< id of entries_.front()
    std::uint64_t next_id_ = 1;
    std::size_t pending_ = 0;
    std::size_t pending_acknowledged_ = 0;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
