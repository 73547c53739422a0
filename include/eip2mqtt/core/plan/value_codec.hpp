#pragma once
/// Reading and writing tag values in an exchange's data bytes (docs/protocol.md §3):
/// little-endian, any byte offset, bits by read-modify-write of their byte.

#include <cstddef>
#include <span>

#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"

namespace eip2mqtt::core::plan {

/// Decodes the tag at `address`. Precondition: address.byte + size_of(type) <= data.size().
Value decode_value(std::span<const std::byte> data, TagType type, Address address);

/// Encodes `value` at `address`, converting it to `type` (callers validate ranges first; a value
/// of another alternative is converted as by static_cast). Bits change only their own bit.
/// Precondition: address.byte + size_of(type) <= data.size().
void encode_value(std::span<std::byte> data, TagType type, Address address, const Value& value);

}  // namespace eip2mqtt::core::plan
