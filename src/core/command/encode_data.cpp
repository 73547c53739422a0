// Read, Write and Masked Write PDUs (docs/protocol.md §9.4).

#include <cassert>

#include "core/command/detail/byte_io.hpp"
#include "core/command/detail/cell_shape.hpp"
#include "core/command/detail/header_io.hpp"
#include "eip2mqtt/core/command/encode.hpp"

namespace eip2mqtt::core::command {
namespace {

using detail::ByteWriter;
using detail::cell_shape;

void put_padded(ByteWriter& out, const std::vector<std::byte>& bytes, std::size_t length) {
    assert(bytes.size() == length);
    out.bytes(bytes);
    out.zeros(padded(length) - length);
}

}  // namespace

std::vector<std::byte> encode(PduHeader header, const DataPdu& pdu) {
    const auto parts = cell_shape(header.type, header.status);
    std::size_t size = data_fixed_size;
    if (parts) {
        for (const auto& cell : pdu.cells) {
            size += cell_head_size + (parts->data + parts->mask) * padded(cell.length);
        }
    }
    std::vector<std::byte> bytes;
    bytes.reserve(size);
    ByteWriter out(bytes);
    detail::put_header(out, header);
    out.u16(pdu.signature);
    out.u8(pdu.address_type);
    out.u8(parts ? static_cast<std::uint8_t>(pdu.cells.size()) : 0);
    out.dotted(pdu.key.producer_id.value);
    out.u32(pdu.key.exchange_id);
    out.u32(pdu.time_s);
    out.u32(pdu.time_ns);
    out.u32(0);
    if (parts) {
        assert(pdu.cells.size() <= 255);
        for (const auto& cell : pdu.cells) {
            out.u16(cell.offset);
            out.u16(cell.length);
            if (parts->data) put_padded(out, cell.data, cell.length);
            if (parts->mask) put_padded(out, cell.mask, cell.length);
        }
    }
    return detail::finish(std::move(bytes));
}

}  // namespace eip2mqtt::core::command
