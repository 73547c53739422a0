#pragma once
// Sparkplug B 3.0 arrays: the elements packed little-endian in a metric's bytes_value; a
// BooleanArray as its count (4 bytes, little-endian) and then its bits, the first in the most
// significant bit of the first byte.

#include <cstdint>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"

namespace eip2mqtt::adapters::sparkplug::detail {

/// The value as an integer of 64 bits (floats truncated; 0 for a Text or a List).
std::int64_t as_int64(const core::plan::Value& value);
std::uint64_t as_uint64(const core::plan::Value& value);

/// The bytes_value of an array of `element`s (a scalar datatype).
std::string array_bytes(DataType element, const std::vector<core::plan::Value>& items);

}  // namespace eip2mqtt::adapters::sparkplug::detail
