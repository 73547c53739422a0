#include "adapters/sparkplug/detail/array_bytes.hpp"

#include <cmath>
#include <limits>
#include <span>
#include <type_traits>
#include <variant>

#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::adapters::sparkplug::detail {
namespace {

void put_le(std::uint64_t bits, std::size_t size, std::string& out) {
    for (std::size_t i = 0; i < size; ++i) out.push_back(static_cast<char>(bits >> (8 * i) & 0xFF));
}

template <class Int>
Int to_integer(const core::plan::Value& value) {
    return std::visit(
        [](const auto& v) -> Int {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, core::plan::Text> ||
                          std::is_same_v<V, core::plan::List>) {
                return 0;
            } else if constexpr (std::is_floating_point_v<V>) {
                // An element of a scaled array that no integer holds (NaN, beyond the type):
                // a cast would be undefined, so 0 or the nearest end.
                if (std::isnan(v)) return 0;
                if (v <= static_cast<V>(std::numeric_limits<Int>::min())) {
                    return std::numeric_limits<Int>::min();
                }
                if (v >= static_cast<V>(std::numeric_limits<Int>::max())) {
                    return std::numeric_limits<Int>::max();
                }
                return static_cast<Int>(v);
            } else {
                return static_cast<Int>(v);
            }
        },
        value);
}

/// The wire type whose little-endian bytes are the element's: its encoding is the exchange's
/// (the narrow types keep the low bytes of an integer's two's complement, as Sparkplug does).
core::plan::TagType wire_type(DataType element) {
    using core::plan::TagType;
    switch (element) {
        case DataType::int8:
        case DataType::uint8:
            return TagType::byte;
        case DataType::int16:
            return TagType::int_;
        case DataType::uint16:
            return TagType::word;
        case DataType::int32:
            return TagType::dint;
        case DataType::uint32:
            return TagType::udint;
        case DataType::float32:
            return TagType::real;
        case DataType::float64:
            return TagType::lreal;
        default:
            return TagType::lint;  // int64, uint64
    }
}

std::string boolean_bytes(const std::vector<core::plan::Value>& items) {
    std::string out;
    put_le(items.size(), 4, out);
    out.resize(4 + (items.size() + 7) / 8, '\0');
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (core::plan::to_double(items[i]) != 0.0)
            out[4 + i / 8] |= static_cast<char>(0x80 >> (i % 8));
    }
    return out;
}

}  // namespace

std::int64_t as_int64(const core::plan::Value& value) { return to_integer<std::int64_t>(value); }

std::uint64_t as_uint64(const core::plan::Value& value) { return to_integer<std::uint64_t>(value); }

std::string array_bytes(DataType element, const std::vector<core::plan::Value>& items) {
    if (element == DataType::boolean) return boolean_bytes(items);
    const auto type = wire_type(element);
    const auto size = core::plan::size_of(type);
    std::string out(items.size() * size, '\0');
    const auto bytes = std::as_writable_bytes(std::span(out.data(), out.size()));
    for (std::size_t i = 0; i < items.size(); ++i) {
        core::plan::encode_value(bytes, type, {static_cast<std::uint16_t>(i * size), 0}, items[i]);
    }
    return out;
}

}  // namespace eip2mqtt::adapters::sparkplug::detail
