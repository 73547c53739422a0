#pragma once
/// What a responder knows of one of its exchanges when a request comes: configuration, state,
/// counters and current image, gathered by the caller at that moment (the gateway from its
/// running exchanges, `sim` from what it sends). Borrowed for one answer.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "eip2mqtt/core/command/exchange_pdus.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::command {

struct ExchangeView {
    const plan::ExchangePlan* plan = nullptr;
    ExchangeMode mode = ExchangeMode::produced;
    ExchangeState state = ExchangeState::idle;
    DestinationType destination_type = DestinationType::unicast;
    std::uint32_t destination = 0;  ///< IPv4, host order (a ProducerId's order)
    std::uint16_t port = 0;         ///< of the data
    std::uint32_t config_time_s = 0;
    std::uint32_t due_time_ms = 0;
    std::uint32_t messages = 0;
    std::uint32_t missed = 0;
    std::uint32_t refresh_errors = 0;
    /// The produced image, or a consumed exchange's last accepted data; empty: none yet.
    std::span<const std::byte> image;
    std::uint32_t time_s = 0;  ///< when the image was sampled
    std::uint32_t time_ns = 0;
    /// Whether a write to this exchange is staged (on the exchange of `plan`): false for one
    /// that cannot be written.
    bool writable = false;
};

/// The responding node itself.
struct NodeInfo {
    wire::ProducerId producer_id;  ///< in Summary and Capabilities responses
    std::string identification;    ///< `eip2mqtt 0.1.0`
    bool writes = false;           ///< Write and Masked Write allowed
};

/// A counter of 64 bits in a field of 32: it wraps, as GE's own counters do.
inline std::uint32_t wrap32(std::uint64_t counter) { return static_cast<std::uint32_t>(counter); }

}  // namespace eip2mqtt::core::command
