#include "eip2mqtt/core/wire/encode.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>

namespace eip2mqtt::core::wire {
namespace {

void put_u8(std::span<std::byte> out, std::size_t offset, std::uint32_t value) {
    out[offset] = static_cast<std::byte>(value & 0xFF);
}

void put_u16le(std::span<std::byte> out, std::size_t offset, std::uint16_t value) {
    put_u8(out, offset, value);
    put_u8(out, offset + 1, value >> 8);
}

void put_u32le(std::span<std::byte> out, std::size_t offset, std::uint32_t value) {
    for (std::size_t i = 0; i < 4; ++i) put_u8(out, offset + i, value >> (8 * i));
}

// docs/protocol.md §2: the Producer ID goes out in dotted (network) order.
void put_u32be(std::span<std::byte> out, std::size_t offset, std::uint32_t value) {
    for (std::size_t i = 0; i < 4; ++i) put_u8(out, offset + i, value >> (8 * (3 - i)));
}

}  // namespace

void encode_header(const Header& header, std::span<std::byte> out) {
    assert(out.size() >= header_size);
    put_u8(out, 0, header.pdu_type);
    put_u8(out, 1, header.pdu_version);
    put_u16le(out, 2, header.request_id);
    put_u32be(out, 4, header.producer_id.value);
    put_u32le(out, 8, header.exchange_id);
    put_u32le(out, 12, header.time_s);
    put_u32le(out, 16, header.time_ns);
    put_u32le(out, 20, header.status);
    put_u32le(out, 24, header.signature);
    put_u32le(out, 28, header.reserved);
}

std::size_t encode_datagram(const Header& header, std::span<const std::byte> data,
                            std::span<std::byte> out) {
    assert(!data.empty() && data.size() <= max_data_size);
    assert(out.size() >= header_size + data.size());
    encode_header(header, out);
    std::copy(data.begin(), data.end(), out.begin() + header_size);
    return header_size + data.size();
}

}  // namespace eip2mqtt::core::wire
