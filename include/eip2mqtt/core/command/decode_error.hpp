#pragma once
/// Why a command PDU could not be decoded (docs/protocol.md §9.5). Each value is also a metric
/// label, and the reasons a responder answers with a Command NAK carry a code on the wire.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::command {

enum class DecodeError : std::uint8_t {
    /// Fewer than the 8 header bytes: nothing to answer, not even a request id. Never NAKed.
    no_header,
    /// More than 1400 bytes (§9.1).
    oversized,
    /// Protocol version (byte 4) is not 1.
    wrong_version,
    /// The message length (bytes 6-7) is not the datagram's size.
    wrong_length,
    /// A PDU type that is not in §9.2.
    unknown_type,
    /// Shorter than its type's fixed part, or a cell runs past the end.
    truncated,
    /// A field the PDU cannot have: no cells, an empty cell, bytes after the last field, or
    /// request options (a non-zero option length).
    malformed,
    /// A response or a NAK where a request was expected: never answered, so two nodes can never
    /// answer each other for ever.
    not_a_request,
    /// A request where a response was expected (on the requester's side).
    not_a_response,
};

/// snake_case names, as used in metrics, logs and the NAK's error string.
inline constexpr auto decode_error_names = enum_names<DecodeError>(
    "no_header", "oversized", "wrong_version", "wrong_length", "unknown_type", "truncated",
    "malformed", "not_a_request", "not_a_response");

inline constexpr std::size_t decode_error_count = decode_error_names.size();

inline constexpr auto all_decode_errors = decode_error_names.values();

constexpr std::string_view to_string(DecodeError error) {
    return decode_error_names.name_of(error);
}

/// The NAK error code a responder sends for `error` (§9.5), or nullopt when a responder stays
/// silent (no_header, not_a_request, not_a_response).
std::optional<std::uint16_t> nak_code(DecodeError error);

/// The reason a NAK's error code names, if it is one of ours.
std::optional<DecodeError> decode_error_of_nak_code(std::uint16_t code);

}  // namespace eip2mqtt::core::command
