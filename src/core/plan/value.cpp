#include "eip2mqtt/core/plan/value.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <type_traits>

namespace eip2mqtt::core::plan {
namespace {

// Shortest text that reads back to the same float or double, so a real 1.1f prints "1.1"
// rather than its binary64 widening 1.100000023841858. JSON has no NaN or infinities.
template <class Float>
std::string float_to_json(Float value) {
    if (std::isnan(value)) return "\"NaN\"";
    if (std::isinf(value)) return value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    std::string text(buffer.data(), result.ptr);
    // A real stays a JSON float even when integral (65900.0, not 65900), so that consumers
    // which type fields by their first value (InfluxDB, Telegraf) never see it change type.
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text;
}

}  // namespace

double to_double(const Value& value) {
    return std::visit([](auto v) { return static_cast<double>(v); }, value);
}

std::string to_json(const Value& value) {
    return std::visit(
        [](auto v) -> std::string {
            using V = decltype(v);
            if constexpr (std::is_same_v<V, bool>) {
                return v ? "true" : "false";
            } else if constexpr (std::is_floating_point_v<V>) {
                return float_to_json(v);
            } else {
                return std::to_string(v);
            }
        },
        value);
}

bool same_value(const Value& a, const Value& b) {
    if (a.index() != b.index()) return false;
    return std::visit(
        [&b](auto va) {
            using V = decltype(va);
            const V vb = std::get<V>(b);
            if constexpr (std::is_floating_point_v<V>) {
                if (std::isnan(va) || std::isnan(vb)) return std::isnan(va) && std::isnan(vb);
            }
            return va == vb;
        },
        a);
}

}  // namespace eip2mqtt::core::plan
