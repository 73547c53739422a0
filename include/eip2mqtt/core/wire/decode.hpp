#pragma once
/// Header parsing of received datagrams: the per-datagram rules that need no configuration
/// (docs/protocol.md §4 rules 1 and 2).

#include <cstddef>
#include <span>

#include "eip2mqtt/core/result.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::wire {

/// A datagram whose header is valid. `data` views the caller's buffer.
struct Datagram {
    Header header;
    std::span<const std::byte> data;
};

/// Decodes every header field. Fails with too_short (< 32 bytes), not_data_pdu (bytes 0-1 not
/// 0D 01), no_data (exactly 32 bytes) or too_long (> 1432 bytes). Never reads past `bytes`.
Result<Datagram, DropReason> decode_datagram(std::span<const std::byte> bytes);

/// Decodes the 32 header bytes without any check; `bytes` must hold at least 32 bytes.
Header decode_header(std::span<const std::byte> bytes);

}  // namespace eip2mqtt::core::wire
