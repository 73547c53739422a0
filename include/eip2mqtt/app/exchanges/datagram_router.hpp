#pragma once
/// Every datagram the receiver reads goes through here (docs/architecture.md "One datagram
/// north"): decoded, matched by its key to the consumed exchange it belongs to, checked against
/// that exchange's source, and handed to it; each one dropped on the way is counted by reason
/// and logged without flooding (DropLog).
///
/// Threading: the loop only. Monotonic time is passed in; the wall clock is read only for a
/// datagram handed to its exchange, never for one dropped on the way (a flood of spoofed or
/// malformed datagrams costs no clock reading), and tests replace it.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/app/exchanges/drop_log.hpp"
#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app {

struct DatagramCounters {
    std::uint64_t datagrams = 0;  ///< every datagram read
    std::uint64_t accepted = 0;   ///< applied by their exchange
    std::array<std::uint64_t, core::wire::drop_reason_count> dropped{};
    /// With a role that hears them (UnitRole::hears_produced): datagrams of exchanges this unit
    /// produces, from the other unit (or its own, looped back); not dropped, and not accepted
    /// unless a consumer of the same key took them.
    std::uint64_t produced_heard = 0;

    std::uint64_t dropped_for(core::wire::DropReason reason) const {
        return dropped[static_cast<std::size_t>(reason)];
    }
};

class DatagramRouter {
public:
    /// `clock` stamps each accepted datagram's receive time; it must outlive the router.
    explicit DatagramRouter(const core::Clock& clock = adapters::clock::system_clock())
        : clock_(clock) {}

    /// The consumers datagrams are routed to, replacing the ones before (start, reload). They
    /// must outlive their use here: call again before destroying any.
    void set_consumers(std::span<const std::unique_ptr<ExchangeConsumer>> consumers);

    /// The producers whose datagrams `role` may hear from another unit
    /// (UnitRole::hears_produced): one of their exchanges heard is counted, and while
    /// `role.follows_produced(now)` the producer's request ids continue after the one heard
    /// (docs/redundancy.md). Without a call, or when the role hears none, such datagrams are
    /// unknown ones. They and `role` must outlive their use here: call again before destroying
    /// any.
    void set_followed(std::span<const std::unique_ptr<ExchangeProducer>> producers,
                      const redundancy::UnitRole& role);

    /// One datagram as read from `from`; `truncated`: it did not fit the receive buffer.
    void route(std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
               bool truncated, core::MonoTime now);

    /// Summarises the drops not logged yet (the gateway's tick).
    void flush_log(core::MonoTime now) { drop_log_.flush(now); }

    const DatagramCounters& counters() const { return counters_; }

private:
    /// True when `header` is of an exchange this unit produces (and follows).
    bool heard_produced(const core::wire::Header& header, core::MonoTime now);
    void count_drop(core::wire::DropReason reason) {
        ++counters_.dropped[static_cast<std::size_t>(reason)];
    }

    std::unordered_map<core::wire::ExchangeKey, ExchangeConsumer*, core::wire::ExchangeKeyHash>
        by_key_;
    std::unordered_map<core::wire::ExchangeKey, ExchangeProducer*, core::wire::ExchangeKeyHash>
        produced_;
    const redundancy::UnitRole* role_ = nullptr;  ///< set with produced_
    const core::Clock& clock_;
    DatagramCounters counters_;
    DropLog drop_log_;
};

}  // namespace eip2mqtt::app
