#include "eip2mqtt/core/wire/decode.hpp"

#include <cassert>
#include <cstdint>

namespace eip2mqtt::core::wire {
namespace {

std::uint8_t u8_at(std::span<const std::byte> bytes, std::size_t offset) {
    return std::to_integer<std::uint8_t>(bytes[offset]);
}

std::uint16_t u16le_at(std::span<const std::byte> bytes, std::size_t offset) {
    return static_cast<std::uint16_t>(u8_at(bytes, offset) | u8_at(bytes, offset + 1) << 8);
}

std::uint32_t u32le_at(std::span<const std::byte> bytes, std::size_t offset) {
    return std::uint32_t{u8_at(bytes, offset)} | std::uint32_t{u8_at(bytes, offset + 1)} << 8 |
           std::uint32_t{u8_at(bytes, offset + 2)} << 16 |
           std::uint32_t{u8_at(bytes, offset + 3)} << 24;
}

// docs/protocol.md §2: the Producer ID is the one field sent in dotted (network) order.
std::uint32_t u32be_at(std::span<const std::byte> bytes, std::size_t offset) {
    return std::uint32_t{u8_at(bytes, offset)} << 24 |
           std::uint32_t{u8_at(bytes, offset + 1)} << 16 |
           std::uint32_t{u8_at(bytes, offset + 2)} << 8 | std::uint32_t{u8_at(bytes, offset + 3)};
}

}  // namespace

Header decode_header(std::span<const std::byte> bytes) {
    assert(bytes.size() >= header_size);
    Header header;
    header.pdu_type = u8_at(bytes, 0);
    header.pdu_version = u8_at(bytes, 1);
    header.request_id = u16le_at(bytes, 2);
    header.producer_id = ProducerId{u32be_at(bytes, 4)};
    header.exchange_id = u32le_at(bytes, 8);
    header.time_s = u32le_at(bytes, 12);
    header.time_ns = u32le_at(bytes, 16);
    header.status = u32le_at(bytes, 20);
    header.signature = u32le_at(bytes, 24);
    header.reserved = u32le_at(bytes, 28);
    return header;
}

Result<Datagram, DropReason> decode_datagram(std::span<const std::byte> bytes) {
    // docs/protocol.md §4 rule 1.
    if (bytes.size() < header_size) return fail(DropReason::too_short);
    // §4 rule 2: only `0D 01`; the byte-swapped `01 0D` of some simulators is dropped too.
    if (u8_at(bytes, 0) != pdu_type_data || u8_at(bytes, 1) != pdu_version) {
        return fail(DropReason::not_data_pdu);
    }
    // §4 rule 2: no data, or more than 1400 data bytes (§2).
    if (bytes.size() == header_size) return fail(DropReason::no_data);
    if (bytes.size() > max_datagram_size) return fail(DropReason::too_long);
    return Datagram{decode_header(bytes), bytes.subspan(header_size)};
}

}  // namespace eip2mqtt::core::wire
