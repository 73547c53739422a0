#include "eip2mqtt/core/plan/value_codec.hpp"

#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <variant>

namespace eip2mqtt::core::plan {
namespace {

// docs/protocol.md §3: little-endian at any byte offset, so shifts, never pointer casts.
std::uint64_t load_le(std::span<const std::byte> data, std::size_t offset, std::size_t size) {
    std::uint64_t raw = 0;
    for (std::size_t i = 0; i < size; ++i) {
        raw |= std::uint64_t{std::to_integer<std::uint8_t>(data[offset + i])} << (8 * i);
    }
    return raw;
}

void store_le(std::span<std::byte> data, std::size_t offset, std::size_t size, std::uint64_t raw) {
    for (std::size_t i = 0; i < size; ++i) {
        data[offset + i] = static_cast<std::byte>(raw >> (8 * i) & 0xFF);
    }
}

// A floating value converted to an integer type. static_cast is undefined outside the target's
// range, so NaN becomes 0 and out-of-range values saturate; callers validate ranges first.
template <class Int>
Int float_to_int(double value) {
    if (std::isnan(value)) return 0;
    if (value <= static_cast<double>(std::numeric_limits<Int>::min())) {
        return std::numeric_limits<Int>::min();
    }
    if (value >= static_cast<double>(std::numeric_limits<Int>::max())) {
        return std::numeric_limits<Int>::max();
    }
    return static_cast<Int>(value);
}

template <class Int>
Int to_int(const Value& value) {
    return std::visit(
        [](auto v) -> Int {
            using V = decltype(v);
            if constexpr (std::is_floating_point_v<V>) {
                return float_to_int<Int>(static_cast<double>(v));
            } else {
                return static_cast<Int>(v);
            }
        },
        value);
}

template <class Float>
Float to_float(const Value& value) {
    return std::visit([](auto v) { return static_cast<Float>(v); }, value);
}

}  // namespace

Value decode_value(std::span<const std::byte> data, TagType type, Address address) {
    const std::size_t at = address.byte;
    assert(at + size_of(type) <= data.size());
    switch (type) {
        case TagType::bit:
            // §3: bit 0 is the least significant bit (0x01).
            return (std::to_integer<unsigned>(data[at]) >> address.bit & 1U) != 0;
        case TagType::byte:
            return std::uint64_t{load_le(data, at, 1)};
        case TagType::int_:
            return std::int64_t{
                static_cast<std::int16_t>(static_cast<std::uint16_t>(load_le(data, at, 2)))};
        case TagType::word:
            return std::uint64_t{load_le(data, at, 2)};
        case TagType::dint:
            return std::int64_t{
                static_cast<std::int32_t>(static_cast<std::uint32_t>(load_le(data, at, 4)))};
        case TagType::udint:
            return std::uint64_t{load_le(data, at, 4)};
        case TagType::real:
            return std::bit_cast<float>(static_cast<std::uint32_t>(load_le(data, at, 4)));
        case TagType::lint:
            return static_cast<std::int64_t>(load_le(data, at, 8));
        case TagType::lreal:
            return std::bit_cast<double>(load_le(data, at, 8));
    }
    return false;
}

void encode_value(std::span<std::byte> data, TagType type, Address address, const Value& value) {
    const std::size_t at = address.byte;
    assert(at + size_of(type) <= data.size());
    switch (type) {
        case TagType::bit: {
            // §3: producers write a bit by read-modify-write of its byte.
            const bool set = std::visit([](auto v) { return v != 0; }, value);
            const auto mask = static_cast<std::byte>(1U << address.bit);
            data[at] = set ? (data[at] | mask) : (data[at] & ~mask);
            return;
        }
        case TagType::byte:
            store_le(data, at, 1, to_int<std::uint8_t>(value));
            return;
        case TagType::int_:
            store_le(data, at, 2, static_cast<std::uint16_t>(to_int<std::int16_t>(value)));
            return;
        case TagType::word:
            store_le(data, at, 2, to_int<std::uint16_t>(value));
            return;
        case TagType::dint:
            store_le(data, at, 4, static_cast<std::uint32_t>(to_int<std::int32_t>(value)));
            return;
        case TagType::udint:
            store_le(data, at, 4, to_int<std::uint32_t>(value));
            return;
        case TagType::real:
            store_le(data, at, 4, std::bit_cast<std::uint32_t>(to_float<float>(value)));
            return;
        case TagType::lint:
            store_le(data, at, 8, static_cast<std::uint64_t>(to_int<std::int64_t>(value)));
            return;
        case TagType::lreal:
            store_le(data, at, 8, std::bit_cast<std::uint64_t>(to_float<double>(value)));
            return;
    }
}

}  // namespace eip2mqtt::core::plan
