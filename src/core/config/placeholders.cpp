#include "eip2mqtt/core/config/placeholders.hpp"

#include <algorithm>

namespace eip2mqtt::core::config {
namespace {

/// The key of a `key: value` line (a sequence's `- ` before it skipped), or empty.
std::string key_of(std::string_view line, std::size_t& column) {
    column = line.find_first_not_of(" \t-");
    if (column == std::string_view::npos) return {};
    const auto colon = line.find(':', column);
    if (colon == std::string_view::npos) return {};
    return std::string(line.substr(column, colon - column));
}

/// Whether `line` carries the marker in a comment: after a `#` that begins a comment (at the
/// start or after a blank), not inside a quoted value such as a topic.
bool marked(std::string_view line) {
    for (auto at = line.find(placeholder_marker); at != std::string_view::npos;
         at = line.find(placeholder_marker, at + 1)) {
        const auto before = line.substr(0, at);
        const auto quotes = std::count(before.begin(), before.end(), '"');
        if ((at == 0 || before.back() == ' ' || before.back() == '\t') && quotes % 2 == 0) {
            return true;
        }
    }
    return false;
}

}  // namespace

std::vector<Placeholder> find_placeholders(std::string_view text, const FileName& file) {
    std::vector<Placeholder> found;
    int number = 1;
    for (std::size_t start = 0; start < text.size(); ++number) {
        const auto end = std::min(text.find('\n', start), text.size());
        const auto line = text.substr(start, end - start);
        start = end + 1;
        // A comment line (the header that explains the marker) is no placeholder.
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos || line[first] == '#' || !marked(line)) continue;
        std::size_t column = 0;
        auto key = key_of(line, column);
        found.push_back({{file, number, static_cast<int>(column) + 1}, std::move(key)});
    }
    return found;
}

}  // namespace eip2mqtt::core::config
