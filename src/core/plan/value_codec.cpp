#include "eip2mqtt/core/plan/value_codec.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <variant>

#include "eip2mqtt/core/plan/latin1.hpp"

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

/// `convert` of a scalar alternative; 0 for a Text or a List, which no number encodes.
template <class T, class Convert>
T scalar_as(const Value& value, Convert convert) {
    return std::visit(
        [&convert](const auto& v) -> T {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, Text> || std::is_same_v<V, List>) {
                return T{0};
            } else {
                return convert(v);
            }
        },
        value);
}

template <class Int>
Int to_int(const Value& value) {
    return scalar_as<Int>(value, [](auto v) -> Int {
        if constexpr (std::is_floating_point_v<decltype(v)>) {
            return float_to_int<Int>(static_cast<double>(v));
        } else {
            return static_cast<Int>(v);
        }
    });
}

// Not through double: a float is written back as it was read, a signalling NaN too.
template <class Float>
Float to_float(const Value& value) {
    return scalar_as<Float>(value, [](auto v) { return static_cast<Float>(v); });
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
        case TagType::string:
            return make_text(latin1_to_utf8(data.subspan(at, 1), true));
    }
    return false;
}

void encode_value(std::span<std::byte> data, TagType type, Address address, const Value& value) {
    const std::size_t at = address.byte;
    assert(at + size_of(type) <= data.size());
    switch (type) {
        case TagType::bit: {
            // §3: producers write a bit by read-modify-write of its byte.
            const bool set = to_int<std::uint64_t>(value) != 0;
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
        case TagType::string: {
            TagSpec one_byte;
            one_byte.address = address;
            one_byte.type = TagType::string;
            encode_tag(data, one_byte, value);
            return;
        }
    }
}

std::size_t tag_size(const TagSpec& tag) {
    if (tag.type == TagType::bit) return (std::size_t{tag.address.bit & 7u} + tag.count + 7) / 8;
    return size_of(tag.type) * tag.count;
}

Address element_address(const TagSpec& tag, std::size_t index) {
    if (tag.type == TagType::bit) {
        const std::size_t bit = tag.address.bit + index;
        return {static_cast<std::uint16_t>(tag.address.byte + bit / 8),
                static_cast<std::uint8_t>(bit % 8)};
    }
    return {static_cast<std::uint16_t>(tag.address.byte + index * size_of(tag.type)), 0};
}

Value decode_tag(std::span<const std::byte> data, const TagSpec& tag, Padding padding) {
    if (tag.type == TagType::string) {
        const bool trim = padding == Padding::as_tag && tag.trim();
        return make_text(latin1_to_utf8(data.subspan(tag.address.byte, tag.count), trim));
    }
    if (tag.count <= 1) return decode_value(data, tag.type, tag.address);
    std::vector<Value> items;
    items.reserve(tag.count);
    for (std::size_t i = 0; i < tag.count; ++i) {
        items.push_back(decode_value(data, tag.type, element_address(tag, i)));
    }
    return make_list(std::move(items));
}

void encode_tag(std::span<std::byte> data, const TagSpec& tag, const Value& value) {
    if (tag.type == TagType::string) {
        const auto field = data.subspan(tag.address.byte, tag.count);
        std::fill(field.begin(), field.end(), std::byte{0});
        const auto* text = std::get_if<Text>(&value);
        const auto bytes = text != nullptr ? utf8_to_latin1(**text) : std::nullopt;
        if (bytes) std::memcpy(field.data(), bytes->data(), std::min(field.size(), bytes->size()));
        return;
    }
    const auto* items = list_items(value);
    if (items == nullptr) {
        encode_value(data, tag.type, tag.address, value);
        return;
    }
    for (std::size_t i = 0; i < std::min<std::size_t>(items->size(), tag.count); ++i) {
        encode_value(data, tag.type, element_address(tag, i), (*items)[i]);
    }
}

}  // namespace eip2mqtt::core::plan
