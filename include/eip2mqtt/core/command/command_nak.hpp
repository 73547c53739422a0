#pragma once
/// The Command NAK (docs/protocol.md §9.5): the answer to a request that cannot be understood.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/command/decode_error.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::command {

inline constexpr std::size_t nak_fixed_size = 36;
inline constexpr std::size_t nak_echo_size = 16;

struct CommandNak {
    wire::ExchangeKey key;  ///< from the request when it has them, else 0
    std::uint16_t error_code = 0;
    std::vector<std::byte> offending;  ///< the request's first bytes, at most 16
    std::string error;                 ///< at most 80 characters
    friend bool operator==(const CommandNak&, const CommandNak&) = default;
};

/// The NAK a responder sends for `request`, which failed to decode with `error`, and its
/// header; nullopt when `error` is never answered (decode_error.hpp). The error string is the
/// reason's name: short, so a NAK stays small.
struct NakReply {
    PduHeader header;
    CommandNak nak;
};
std::optional<NakReply> make_nak(std::span<const std::byte> request, DecodeError error);

}  // namespace eip2mqtt::core::command
