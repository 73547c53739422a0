#pragma once
/// The 8-byte header, written and then patched with the PDU's final length.

#include <cassert>
#include <cstddef>
#include <vector>

#include "core/command/detail/byte_io.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::core::command::detail {

inline void put_header(ByteWriter& out, const PduHeader& header) {
    out.u8(static_cast<std::uint8_t>(header.type));
    out.u8(header.flag);
    out.u16(header.request_id);
    out.u8(header.version);
    out.u8(header.status);
    out.u16(0);  // the length, patched by finish()
}

inline std::vector<std::byte> finish(std::vector<std::byte> pdu) {
    assert(pdu.size() >= header_size && pdu.size() <= max_pdu_size);
    pdu[6] = static_cast<std::byte>(pdu.size() & 0xFF);
    pdu[7] = static_cast<std::byte>(pdu.size() >> 8 & 0xFF);
    return pdu;
}

}  // namespace eip2mqtt::core::command::detail
