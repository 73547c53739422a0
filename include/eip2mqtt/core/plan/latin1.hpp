#pragma once
/// String tags carry Latin-1 (ISO 8859-1), as GE controllers and most HMIs write them: each
/// byte is the code point of the same number. MQTT and JSON carry UTF-8.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace eip2mqtt::core::plan {

/// The text of a fixed field of `bytes`, as UTF-8; with `trim`, without its trailing NULs and
/// spaces (the padding of a field longer than its text).
std::string latin1_to_utf8(std::span<const std::byte> bytes, bool trim);

/// The Latin-1 bytes of UTF-8 `text`; nullopt when it is no valid UTF-8 or has a character
/// beyond U+00FF, which Latin-1 has no byte for.
std::optional<std::string> utf8_to_latin1(std::string_view text);

}  // namespace eip2mqtt::core::plan
