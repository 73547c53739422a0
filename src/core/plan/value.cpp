#include "eip2mqtt/core/plan/value.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

#include "eip2mqtt/core/json_text.hpp"

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

Value make_text(std::string utf8) { return Text{std::move(utf8)}; }

Value make_list(std::vector<Value> items) { return List{ValueList{std::move(items)}}; }

const std::vector<Value>* list_items(const Value& value) {
    const auto* list = std::get_if<List>(&value);
    return list != nullptr ? &(*list)->items : nullptr;
}

double to_double(const Value& value) {
    return std::visit(
        [](const auto& v) -> double {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, Text> || std::is_same_v<V, List>) {
                return std::numeric_limits<double>::quiet_NaN();
            } else {
                return static_cast<double>(v);
            }
        },
        value);
}

std::string to_json(const Value& value) {
    return std::visit(
        [](const auto& v) -> std::string {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, bool>) {
                return v ? "true" : "false";
            } else if constexpr (std::is_floating_point_v<V>) {
                return float_to_json(v);
            } else if constexpr (std::is_same_v<V, Text>) {
                std::string out;
                append_json_string(out, *v);
                return out;
            } else if constexpr (std::is_same_v<V, List>) {
                std::string out = "[";
                for (const auto& item : v->items) {
                    if (out.size() > 1) out += ',';
                    out += to_json(item);
                }
                return out + ']';
            } else {
                return std::to_string(v);
            }
        },
        value);
}

bool same_value(const Value& a, const Value& b) {
    if (a.index() != b.index()) return false;
    return std::visit(
        [&b](const auto& va) {
            using V = std::decay_t<decltype(va)>;
            const V& vb = std::get<V>(b);
            if constexpr (std::is_same_v<V, Text>) {
                return *va == *vb;
            } else if constexpr (std::is_same_v<V, List>) {
                return std::equal(va->items.begin(), va->items.end(), vb->items.begin(),
                                  vb->items.end(), same_value);
            } else {
                if constexpr (std::is_floating_point_v<V>) {
                    if (std::isnan(va) || std::isnan(vb)) return std::isnan(va) && std::isnan(vb);
                }
                return va == vb;
            }
        },
        a);
}

}  // namespace eip2mqtt::core::plan
