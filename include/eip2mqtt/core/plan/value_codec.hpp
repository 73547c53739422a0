#pragma once
/// Reading and writing tag values in an exchange's data bytes (docs/protocol.md §3):
/// little-endian, any byte offset, bits by read-modify-write of their byte.

#include <cstddef>
#include <span>

#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"

namespace eip2mqtt::core::plan {

/// Decodes the tag at `address`. Precondition: address.byte + size_of(type) <= data.size().
Value decode_value(std::span<const std::byte> data, TagType type, Address address);

/// Encodes `value` at `address`, converting it to `type` (callers validate ranges first; a value
/// of another alternative is converted as by static_cast). Bits change only their own bit.
/// Precondition: address.byte + size_of(type) <= data.size().
void encode_value(std::span<std::byte> data, TagType type, Address address, const Value& value);

/// Bytes a tag occupies from its address's byte: `count` elements (bits: the bytes its bits
/// reach), a string's length.
std::size_t tag_size(const TagSpec& tag);

/// The address of element `index` of an array tag: the next element starts where the one
/// before ends, the next bit after bit 7 is bit 0 of the next byte.
Address element_address(const TagSpec& tag, std::size_t index);

/// What a string's trailing NULs and spaces become: as the tag's `trim` says, or kept.
enum class Padding : std::uint8_t { as_tag, keep };

/// Decodes the whole tag: a scalar, a List of `count` elements, or a string's Text (Latin-1
/// made UTF-8, trimmed as `padding` says). Precondition: the tag lies within `data`.
Value decode_tag(std::span<const std::byte> data, const TagSpec& tag,
                 Padding padding = Padding::as_tag);

/// Encodes a value of the tag: a scalar, a List of `count` scalars, or a Text of at most
/// `count` Latin-1 bytes, already validated (write validation makes them); a string is padded
/// with NULs. Precondition: the tag lies within `data`.
void encode_tag(std::span<std::byte> data, const TagSpec& tag, const Value& value);

}  // namespace eip2mqtt::core::plan
