#pragma once
/// A decoded tag value. Reals keep their binary32 precision so that they print as the PLC
/// engineer wrote them (1.1, not 1.100000023841858).

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "eip2mqtt/core/plan/shared_value.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::core::plan {

struct ValueList;

/// A string tag's text, as UTF-8. Shared and immutable, so that a Value stays cheap to copy.
using Text = Shared<std::string>;
/// An array tag's elements, each a scalar. Shared and immutable, as Text.
using List = Shared<ValueList>;

/// bit -> bool; byte, word, udint -> uint64; int, dint, lint -> int64; real -> float;
/// lreal -> double; string -> Text; any type with a `count` -> List. A Text or List is never
/// null.
using Value = std::variant<bool, std::int64_t, std::uint64_t, float, double, Text, List>;

struct ValueList {
    std::vector<Value> items;
    friend bool operator==(const ValueList&, const ValueList&) = default;
};

Value make_text(std::string utf8);
Value make_list(std::vector<Value> items);

/// True for a Text or a List: a value no number stands for.
inline bool is_composite(const Value& value) { return value.index() >= 5; }

/// A List's elements; nullptr for any other value.
const std::vector<Value>* list_items(const Value& value);

/// The value as a double (bools are 0/1), for deadband comparisons and range checks; NaN for
/// a Text or a List.
double to_double(const Value& value);

/// JSON text of the value: `true`, `-2`, `1.5`, `"text"`, `[1,2]`. NaN and infinities, which
/// JSON lacks, are written as the strings "NaN", "Infinity", "-Infinity".
std::string to_json(const Value& value);

/// Appends the JSON text of `value` to `out`: `to_json` without a string of its own, for the
/// payloads formatted for every tag change.
void append_json(std::string& out, const Value& value);

/// True when both hold the same alternative and equal values (a List element by element); NaN
/// equals NaN here so that a NaN on the wire is not reported as a change on every datagram.
bool same_value(const Value& a, const Value& b);

}  // namespace eip2mqtt::core::plan
