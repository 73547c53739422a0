#pragma once
/// The Connection's view for other threads: whether it is connected, and its counters. Written
/// on the loop (received: on Paho's thread), read by connected() and stats() from any thread.
///
/// Module-private (src/adapters/mqtt/detail).

#include <atomic>
#include <cstdint>

#include "eip2mqtt/adapters/mqtt/client.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

struct ConnectionCounters {
    std::atomic<bool> connected{false};  ///< the loop's view
    std::atomic<std::uint64_t> connects{0};
    std::atomic<std::uint64_t> connection_losses{0};
    std::atomic<std::uint64_t> received{0};  ///< messages received on subscriptions

    /// Adds one to `counter`.
    static void bump(std::atomic<std::uint64_t>& counter) {
        counter.fetch_add(1, std::memory_order_relaxed);
    }

    /// Fills the fields of `stats` they count.
    void add_to(ClientStats& stats) const {
        stats.connected = connected;
        stats.connects = connects;
        stats.connection_losses = connection_losses;
        stats.received = received;
    }
};

}  // namespace eip2mqtt::adapters::mqtt::detail
