#pragma once
/// Encoding of produced datagrams (docs/protocol.md §2, §5).

#include <cstddef>
#include <span>

#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::wire {

/// Writes the 32 header bytes into `out` (which must hold at least 32 bytes).
void encode_header(const Header& header, std::span<std::byte> out);

/// Writes header + data into `out`; returns the datagram size (32 + data.size()).
/// `out` must hold 32 + data.size() bytes; data.size() must be 1..1400.
std::size_t encode_datagram(const Header& header, std::span<const std::byte> data,
                            std::span<std::byte> out);

}  // namespace eip2mqtt::core::wire
