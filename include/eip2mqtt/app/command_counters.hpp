#pragma once
/// What the command responder counts (docs/mqtt-api.md, metrics `commands`).

#include <array>
#include <cstddef>
#include <cstdint>

#include "eip2mqtt/core/command/decode_error.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::app {

/// The request types, in the order CommandCounters::requests counts them.
inline constexpr std::array<core::command::PduType, 7> command_request_types{
    core::command::PduType::retrieve_config_request,
    core::command::PduType::summary_request,
    core::command::PduType::capabilities_request,
    core::command::PduType::statistics_request,
    core::command::PduType::read_request,
    core::command::PduType::write_request,
    core::command::PduType::masked_write_request,
};

/// The index of a request type in command_request_types.
constexpr std::size_t request_index(core::command::PduType type) {
    for (std::size_t i = 0; i < command_request_types.size(); ++i) {
        if (command_request_types[i] == type) return i;
    }
    return 0;
}

struct CommandCounters {
    /// Requests understood and answered, by type.
    std::array<std::uint64_t, command_request_types.size()> requests{};
    /// Of those, answered with a non-zero status (an unknown exchange, a write refused...).
    std::uint64_t errors = 0;
    /// Datagrams from a source outside `allow`: never answered.
    std::uint64_t refused = 0;
    /// Datagrams over `max_requests_per_s`: never answered.
    std::uint64_t dropped = 0;
    /// Requests that could not be understood, answered with a NAK, by reason.
    std::array<std::uint64_t, core::command::decode_error_count> naks{};
    /// Datagrams not answered at all: no header, or a response or a NAK.
    std::uint64_t ignored = 0;
};

}  // namespace eip2mqtt::app
