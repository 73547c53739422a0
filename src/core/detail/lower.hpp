#pragma once
/// ASCII lower case, for names compared without case (tag types, tag names).
///
/// Module-private to src/core.

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace eip2mqtt::core::detail {

inline std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

}  // namespace eip2mqtt::core::detail
