#pragma once
/// The status byte of a response (byte 5; docs/protocol.md §9.4): why a request that was
/// understood could not be served. 0 is success. The values are eip2mqtt's: the public
/// descriptions of the protocol define none but 0.

#include <cstdint>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::command {

enum class CommandStatus : std::uint8_t {
    success = 0,
    /// No configured exchange has this (producer id, exchange id).
    unknown_exchange = 1,
    /// Writes are off, the exchange is consumed, or a byte written is not inside a writable tag.
    not_permitted = 2,
    /// A cell lies outside the exchange, or the response would exceed 1400 bytes.
    out_of_range = 3,
    /// The write checks refused a value (type range, min/max, rate limit, overlap, queue full).
    rejected = 4,
    /// The request's configuration signature is set and is not the exchange's.
    signature_mismatch = 5,
    /// An address type other than 0 (offsets within an exchange).
    unsupported_address = 6,
    /// A consumed exchange that has accepted no datagram yet: nothing to read.
    no_data = 7,
    /// The write was accepted but its datagram or its image could not be sent or saved.
    failed = 8,
    /// The requester has not proved its address (§9.7) and the answer would be larger than its
    /// request, or it asked to write: the response carries the token to ask again with.
    prove_address = 9,
};

inline constexpr auto command_status_names = enum_names<CommandStatus>(
    "success", "unknown_exchange", "not_permitted", "out_of_range", "rejected",
    "signature_mismatch", "unsupported_address", "no_data", "failed", "prove_address");

constexpr std::string_view to_string(CommandStatus status) {
    return command_status_names.name_of(status);
}
std::optional<CommandStatus> command_status_of(std::uint8_t byte);

}  // namespace eip2mqtt::core::command
