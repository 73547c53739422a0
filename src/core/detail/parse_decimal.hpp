#pragma once
/// Plain decimal digits as the configuration writes numbers inside a dotted form (a tag's
/// `byte.bit`, a producer id's `a.b.c.d`, a signature's `major.minor`).
///
/// Module-private to src/core.

#include <charconv>
#include <string_view>
#include <system_error>

namespace eip2mqtt::core::detail {

/// Reads `text` into `out` when it is one or more digits and nothing else (no sign, no space)
/// and fits `T`; false otherwise, `out` then unspecified.
template <class T>
bool parse_decimal(std::string_view text, T& out) {
    if (text.empty()) return false;
    for (char c : text) {
        if (c < '0' || c > '9') return false;
    }
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc{} && end == text.data() + text.size();
}

}  // namespace eip2mqtt::core::detail
