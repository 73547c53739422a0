#pragma once
/// JSON string literals, for the payloads the gateway writes by hand (a tag's text, a name).

#include <string>
#include <string_view>

namespace eip2mqtt::core {

/// Appends `text` as a JSON string: quoted, `"` and `\` escaped, control characters as `\n` or
/// `\u0001`, never raw; other bytes (UTF-8) as they are.
void append_json_string(std::string& out, std::string_view text);

}  // namespace eip2mqtt::core
