#pragma once
/// What the command responder counts (docs/mqtt-api.md, metrics `commands`), and their table:
/// the one place their names are written (core/counter_table.hpp). Pure.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "eip2mqtt/core/command/decode_error.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"
#include "eip2mqtt/core/counter_table.hpp"

namespace eip2mqtt::core::command {

/// The request types, in the order CommandCounters::requests counts them.
inline constexpr std::array<PduType, 7> command_request_types{
    PduType::retrieve_config_request, PduType::summary_request, PduType::capabilities_request,
    PduType::statistics_request,      PduType::read_request,    PduType::write_request,
    PduType::masked_write_request,
};

/// The index of a request type in command_request_types.
constexpr std::size_t request_index(PduType type) {
    for (std::size_t i = 0; i < command_request_types.size(); ++i) {
        if (command_request_types[i] == type) return i;
    }
    return 0;
}

struct CommandCounters {
    /// Requests understood and answered with their response, by type (not those challenged).
    std::array<std::uint64_t, command_request_types.size()> requests{};
    /// Of those, answered with a non-zero status (an unknown exchange, a write refused...).
    std::uint64_t errors = 0;
    /// Datagrams from a source outside `allow`: never answered.
    std::uint64_t refused = 0;
    /// Datagrams over `max_requests_per_s` or `max_requests_per_s_per_source`: never answered.
    std::uint64_t dropped = 0;
    /// Of `dropped`, those over their source's own limit.
    std::uint64_t dropped_per_source = 0;
    /// Requests from requesters that have not proved their address (docs/protocol.md §9.7),
    /// answered with a challenge: a write, or an answer larger than the request.
    std::uint64_t challenged = 0;
    /// Requests that could not be understood, answered with a NAK, by reason.
    std::array<std::uint64_t, decode_error_count> naks{};
    /// Datagrams not answered at all: no header, a response or a NAK, or a request whose NAK
    /// would be larger than it, from a requester that has not proved its address.
    std::uint64_t ignored = 0;
};

/// The set's name: its object on the metrics topic, the prefix of its Prometheus families.
inline constexpr std::string_view command_counters_name = "commands";

/// A request type's key: its name without `_request` (`read`).
inline std::string_view request_key(std::size_t index) {
    auto name = to_string(command_request_types[index]);
    name.remove_suffix(std::string_view("_request").size());
    return name;
}

/// A reason's key; none for the reasons never answered with a NAK, which are counted in
/// `ignored` instead.
inline std::string_view nak_key(std::size_t index) {
    const auto error = static_cast<DecodeError>(index);
    return nak_code(error) ? to_string(error) : std::string_view{};
}

using CommandCounterField = GatewayCounterField<CommandCounters>;

// clang-format off
inline constexpr std::array<CommandCounterField, 8> command_counter_fields{{
    {"requests",
     [](const CommandCounters& c) { return std::span<const std::uint64_t>(c.requests); },
     in_metrics_topic | in_prometheus, "Command requests answered, by type", request_key, "type"},
    {"errors", [](const CommandCounters& c) { return one(c.errors); },
     in_metrics_topic | in_prometheus, "Command requests answered with an error status"},
    {"refused", [](const CommandCounters& c) { return one(c.refused); },
     in_metrics_topic | in_prometheus,
     "Command datagrams from sources outside eip.commands.allow, unanswered"},
    {"dropped", [](const CommandCounters& c) { return one(c.dropped); },
     in_metrics_topic | in_prometheus,
     "Command datagrams over eip.commands.max_requests_per_s or its per-source limit, "
     "unanswered"},
    {"dropped_per_source", [](const CommandCounters& c) { return one(c.dropped_per_source); },
     in_metrics_topic | in_prometheus,
     "Command datagrams over eip.commands.max_requests_per_s_per_source, unanswered"},
    {"challenged", [](const CommandCounters& c) { return one(c.challenged); },
     in_metrics_topic | in_prometheus,
     "Command requests from requesters that have not proved their address, answered with a "
     "challenge"},
    {"naks", [](const CommandCounters& c) { return std::span<const std::uint64_t>(c.naks); },
     in_metrics_topic | in_prometheus, "Command requests answered with a NAK, by reason", nak_key,
     "reason"},
    {"ignored", [](const CommandCounters& c) { return one(c.ignored); },
     in_metrics_topic | in_prometheus,
     "Command datagrams without a header, not requests, or NAKs larger than an unproven "
     "request, unanswered"},
}};
// clang-format on

static_assert(counts_every_member<CommandCounters>(command_counter_fields),
              "every command counter is read once by command_counter_fields");

}  // namespace eip2mqtt::core::command
