#pragma once
/// Tag data types of docs/protocol.md §3 and their names in YAML and in SCADA point lists.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::plan {

/// The wire types. Every value is little-endian and may start at any byte offset.
enum class TagType : std::uint8_t {
    bit,     ///< one bit of a byte; bit 0 is the least significant
    byte,    ///< u8 (alias usint)
    int_,    ///< i16 (the spec's `int`; a keyword in C++)
    word,    ///< u16 (alias uint)
    dint,    ///< i32
    udint,   ///< u32 (alias dword)
    real,    ///< IEEE-754 binary32
    lint,    ///< i64 (alias long)
    lreal,   ///< IEEE-754 binary64
    string,  ///< a fixed field of Latin-1 bytes (its `length` is the tag's count)
};

/// Which naming convention a type name comes from: they disagree on `word`.
enum class TypeNaming {
    yaml,        ///< §3 names and aliases, case-insensitive: `word` is u16
    point_list,  ///< §6: Bit/Word/Real/Long read as bit/int/real/lint, then the §3 names
};

/// Parses a type name; nullopt when unknown.
std::optional<TagType> parse_tag_type(std::string_view name, TypeNaming naming);

/// What a name that is no type most likely means, for a message: the type other languages
/// and PLC vendors call it (`float` is `real`, `double` is `lreal`, `int32` is `dint`...), or
/// the YAML name it is a typo of; nullopt when nothing is close.
std::optional<std::string_view> tag_type_hint(std::string_view unknown);

/// The aliases YAML takes beside the canonical names, for a message: "bool, usint, uint...".
inline constexpr std::string_view tag_type_aliases = "bool, usint, uint, dword, long";

/// The canonical §3 names (`int`, `udint`...).
inline constexpr auto tag_type_names = enum_names<TagType>(
    "bit", "byte", "int", "word", "dint", "udint", "real", "lint", "lreal", "string");

constexpr std::string_view to_string(TagType type) { return tag_type_names.name_of(type); }

/// Size in bytes one element of this type occupies (1 for bit: it lives in one byte; 1 for
/// string: one character).
std::size_t size_of(TagType type);

/// True for the types whose value is an integer (not bit, real, lreal or string).
bool is_integer(TagType type);

/// The type's own range as doubles, for range checks of configuration and writes (lint's
/// extremes round to the nearest double; exact integer checks are write validation's job).
double type_min(TagType type);
double type_max(TagType type);

}  // namespace eip2mqtt::core::plan
