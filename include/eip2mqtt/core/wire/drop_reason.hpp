#pragma once
/// Why a received datagram was not consumed. Each value is also a metric label.

#include <array>
#include <cstdint>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::wire {

enum class DropReason : std::uint8_t {
    /// Fewer than 32 bytes (§4 rule 1).
    too_short,
    /// Bytes 0-1 are not `0D 01` (§4 rule 2).
    not_data_pdu,
    /// More than 32 + 1400 bytes (§4 rule 2).
    too_long,
    /// No configured consumed exchange has this (producer id, exchange id) (§4 rule 3).
    unknown_exchange,
    /// The source address is not the exchange's configured `source` (anti-spoofing).
    wrong_source,
    /// Header only, no data (§4 rule 2).
    no_data,
    /// Signatures incompatible (§4 rule 4).
    signature_mismatch,
    /// Data length differs from the configured length (§4 rule 5).
    length_mismatch,
    /// Same request id as the last accepted one (§4 rule 6, d = 0).
    duplicate,
    /// Request id behind the last accepted one (§4 rule 6, d >= 32768).
    out_of_order,
};

/// snake_case names, as used in metrics and logs.
inline constexpr auto drop_reason_names = enum_names<DropReason>(
    "too_short", "not_data_pdu", "too_long", "unknown_exchange", "wrong_source", "no_data",
    "signature_mismatch", "length_mismatch", "duplicate", "out_of_order");

inline constexpr std::size_t drop_reason_count = drop_reason_names.size();

inline constexpr std::array<DropReason, drop_reason_count> all_drop_reasons =
    drop_reason_names.values();

constexpr std::string_view to_string(DropReason reason) {
    return drop_reason_names.name_of(reason);
}

}  // namespace eip2mqtt::core::wire
