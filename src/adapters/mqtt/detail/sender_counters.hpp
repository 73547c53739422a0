#pragma once
/// The Sender's counters of what became of the publications: bumped where it happens (the
/// sender's thread, Paho's threads, the loop), read by stats() from any thread. Relaxed
/// atomics: each is a count on its own, read with no order against the others.
///
/// Module-private (src/adapters/mqtt/detail).

#include <atomic>
#include <cstdint>

#include "eip2mqtt/adapters/mqtt/client.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

struct SenderCounters {
    std::atomic<std::uint64_t> published{0};  ///< completed (QoS 0 written, QoS 1 acknowledged)
    std::atomic<std::uint64_t> publish_failures{0};
    std::atomic<std::uint64_t> refused{0};    ///< a broker would refuse it, or a suspect dropped
    std::atomic<std::uint64_t> discarded{0};  ///< session-bound drops, ClientOptions::may_send

    /// Adds one to `counter`.
    static void bump(std::atomic<std::uint64_t>& counter, std::uint64_t by = 1) {
        counter.fetch_add(by, std::memory_order_relaxed);
    }

    /// Fills the fields of `stats` they count.
    void add_to(ClientStats& stats) const {
        stats.published = published.load(std::memory_order_relaxed);
        stats.publish_failures = publish_failures.load(std::memory_order_relaxed);
        stats.refused = refused.load(std::memory_order_relaxed);
        stats.discarded = discarded.load(std::memory_order_relaxed);
    }
};

}  // namespace eip2mqtt::adapters::mqtt::detail
