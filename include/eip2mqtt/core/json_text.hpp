#pragma once
/// JSON string literals and numbers, for the payloads the gateway writes by hand (a tag's
/// text, a name, a timestamp).

#include <array>
#include <charconv>
#include <concepts>
#include <string>
#include <string_view>

namespace eip2mqtt::core {

/// Appends `text` as a JSON string: quoted, `"` and `\` escaped, control characters as `\n` or
/// `\u0001`, never raw; other bytes (UTF-8) as they are.
void append_json_string(std::string& out, std::string_view text);

/// Appends `value` in decimal, as std::to_string writes it, without a string of its own.
template <std::integral Integer>
void append_integer(std::string& out, Integer value) {
    std::array<char, 24> digits{};  // 20 digits and a sign for any 64-bit integer
    const auto end = std::to_chars(digits.data(), digits.data() + digits.size(), value).ptr;
    out.append(digits.data(), end);
}

}  // namespace eip2mqtt::core
