#include "eip2mqtt/core/plan/value.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <type_traits>

#include "eip2mqtt/core/json_text.hpp"

namespace eip2mqtt::core::plan {
namespace {

// Shortest text that reads back to the same float or double, so a real 1.1f prints "1.1"
// rather than its binary64 widening 1.100000023841858. JSON has no NaN or infinities.
template <class Float>
void append_float(std::string& out, Float value) {
    if (std::isnan(value)) {
        out += "\"NaN\"";
        return;
    }
    if (std::isinf(value)) {
        out += value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
        return;
    }
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    const std::string_view text(buffer.data(),
                                static_cast<std::size_t>(result.ptr - buffer.data()));
    out += text;
    // A real stays a JSON float even when integral (65900.0, not 65900), so that consumers
    // which type fields by their first value (InfluxDB, Telegraf) never see it change type.
    if (text.find_first_of(".e") == std::string_view::npos) out += ".0";
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

void append_json(std::string& out, const Value& value) {
    std::visit(
        [&out](const auto& v) {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, bool>) {
                out += v ? "true" : "false";
            } else if constexpr (std::is_floating_point_v<V>) {
                append_float(out, v);
            } else if constexpr (std::is_same_v<V, Text>) {
                append_json_string(out, *v);
            } else if constexpr (std::is_same_v<V, List>) {
                out += '[';
                bool first = true;
                for (const auto& item : v->items) {
                    if (!first) out += ',';
                    first = false;
                    append_json(out, item);
                }
                out += ']';
            } else {
                append_integer(out, v);
            }
        },
        value);
}

std::string to_json(const Value& value) {
    std::string out;
    append_json(out, value);
    return out;
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
