#pragma once
/// The placeholders `import-points` writes into a configuration: values it cannot know (the
/// producer's id, the destination, the length, the period), each marked on its line with a
/// `# PLACEHOLDER` comment that `check` finds and warns about until the line is reviewed and
/// the comment removed. A comment, because the value itself is valid (0.0.0.0, 100 ms) and
/// YAML parsers drop comments: the text is scanned, not the model. Pure: the caller reads the
/// file.

#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/config/diagnostic.hpp"

namespace eip2mqtt::core::config {

/// The comment that marks a placeholder, as written after the value.
inline constexpr std::string_view placeholder_marker = "# PLACEHOLDER";

struct Placeholder {
    Mark mark;        ///< the line, at the key's column
    std::string key;  ///< `producer_id`, `length`...
};

/// Each line of `text` that carries placeholder_marker in a comment, in file order.
std::vector<Placeholder> find_placeholders(std::string_view text, const FileName& file);

}  // namespace eip2mqtt::core::config
