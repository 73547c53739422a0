#include "adapters/sparkplug/detail/array_bytes.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

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

std::size_t size_of(DataType element) {
    switch (element) {
        case DataType::int8:
        case DataType::uint8:
            return 1;
        case DataType::int16:
        case DataType::uint16:
            return 2;
        case DataType::int32:
        case DataType::uint32:
        case DataType::float32:
            return 4;
        default:
            return 8;
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
    std::string out;
    const auto size = size_of(element);
    out.reserve(items.size() * size);
    for (const auto& item : items) {
        if (element == DataType::float32) {
            put_le(std::bit_cast<std::uint32_t>(static_cast<float>(core::plan::to_double(item))), 4,
                   out);
        } else if (element == DataType::float64) {
            put_le(std::bit_cast<std::uint64_t>(core::plan::to_double(item)), 8, out);
        } else {
            // Two's complement: the low bytes of the 64-bit form are the narrower type's.
            put_le(static_cast<std::uint64_t>(as_int64(item)), size, out);
        }
    }
    return out;
}

}  // namespace eip2mqtt::adapters::sparkplug::detail
