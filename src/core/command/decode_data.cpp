// Read, Write and Masked Write PDUs (docs/protocol.md §9.4).

#include "core/command/detail/byte_io.hpp"
#include "core/command/detail/cell_shape.hpp"
#include "eip2mqtt/core/command/decode.hpp"

namespace eip2mqtt::core::command {
namespace {

using detail::ByteReader;
using detail::cell_shape;
using detail::CellShape;

Result<std::vector<Cell>, DecodeError> cells_at(ByteReader& in, std::size_t count,
                                                CellShape shape) {
    std::vector<Cell> cells;
    cells.reserve(count);
    std::size_t at = data_fixed_size;
    for (std::size_t i = 0; i < count; ++i) {
        if (in.size() < at + cell_head_size) return fail(DecodeError::truncated);
        Cell cell;
        cell.offset = in.u16(at);
        cell.length = in.u16(at + 2);
        at += cell_head_size;
        if (cell.length == 0) return fail(DecodeError::malformed);
        for (auto* field : {shape.data ? &cell.data : nullptr, shape.mask ? &cell.mask : nullptr}) {
            if (field == nullptr) continue;
            const auto bytes = in.bytes(at, cell.length);
            if (in.overrun() || in.size() < at + padded(cell.length)) {
                return fail(DecodeError::truncated);
            }
            field->assign(bytes.begin(), bytes.end());
            at += padded(cell.length);
        }
        cells.push_back(std::move(cell));
    }
    if (at != in.size()) return fail(DecodeError::malformed);
    return cells;
}

}  // namespace

Result<DataPdu, DecodeError> decode_data_pdu(const PduHeader& header,
                                             std::span<const std::byte> bytes) {
    ByteReader in(bytes);
    if (in.size() < data_fixed_size) return fail(DecodeError::truncated);
    const bool request = is_request(header.type);
    // §9.4: byte 5 is the option length in a request; options are not defined, so none.
    if (request && header.status != 0) return fail(DecodeError::malformed);
    DataPdu pdu;
    pdu.signature = in.u16(8);
    pdu.address_type = in.u8(10);
    const std::size_t count = in.u8(11);
    pdu.key = {wire::ProducerId{in.dotted(12)}, in.u32(16)};
    pdu.time_s = in.u32(20);
    pdu.time_ns = in.u32(24);
    const auto shape = cell_shape(header.type, header.status);
    if (!shape) return pdu;
    if (request && count == 0) return fail(DecodeError::malformed);
    auto cells = cells_at(in, count, *shape);
    if (!cells) return fail(cells.error());
    pdu.cells = std::move(cells).value();
    return pdu;
}

std::size_t read_response_size(const std::vector<Cell>& cells) {
    std::size_t size = data_fixed_size;
    for (const auto& cell : cells) size += cell_head_size + padded(cell.length);
    return size;
}

}  // namespace eip2mqtt::core::command
