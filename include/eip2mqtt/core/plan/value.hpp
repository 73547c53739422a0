#pragma once
/// A decoded tag value. Reals keep their binary32 precision so that they print as the PLC
/// engineer wrote them (1.1, not 1.100000023841858).

#include <cstdint>
#include <string>
#include <variant>

#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::core::plan {

/// bit -> bool; byte, word, udint -> uint64; int, dint, lint -> int64; real -> float;
/// lreal -> double.
using Value = std::variant<bool, std::int64_t, std::uint64_t, float, double>;

/// The value as a double (bools are 0/1), for deadband comparisons and range checks.
double to_double(const Value& value);

/// JSON text of the value: `true`, `-2`, `1.5`. NaN and infinities, which JSON lacks, are
/// written as the strings "NaN", "Infinity", "-Infinity".
std::string to_json(const Value& value);

/// True when both hold the same alternative and equal values; NaN equals NaN here so that a
/// NaN on the wire is not reported as a change on every datagram.
bool same_value(const Value& a, const Value& b);

}  // namespace eip2mqtt::core::plan
