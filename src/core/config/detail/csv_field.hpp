#pragma once
/// One field of a point list's CSV line, as point_list.cpp splits it.
///
/// Module-private to src/core/config.

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace eip2mqtt::core::config::detail {

struct CsvField {
    std::string_view text;  ///< into the line, or into `unquoted` for a quoted field
    std::string unquoted;   ///< a quoted field without its quotes and with "" read as "
    int column = 1;         ///< 1-based column where the field starts
    bool quoted = false;
};

/// Whether `text` is `lower_case` in any case.
inline bool equals_lower(std::string_view text, std::string_view lower_case) {
    return std::equal(text.begin(), text.end(), lower_case.begin(), lower_case.end(),
                      [](unsigned char a, unsigned char b) { return std::tolower(a) == b; });
}

}  // namespace eip2mqtt::core::config::detail
