#pragma once
/// Names of the generated Wireshark plugin: configured exchange and tag names made into parts of
/// display-filter field names, and any text made into a Lua string literal.

#include <string>
#include <string_view>
#include <unordered_set>

namespace eip2mqtt::app::dissector {

/// `name` as one part of a field name: every character Wireshark refuses in one (anything but
/// ASCII letters, digits, `_` and `-`, the dot included, which separates parts) becomes `_`, a
/// multi-byte UTF-8 character a single `_`. Empty stays empty.
std::string field_part(std::string_view name);

/// Hands out field-name parts that are unique within one scope (the exchanges, or the tags of
/// one exchange): two names that escape alike, or a name equal to a reserved part, get `_2`,
/// `_3`... in the order they are asked for, so the same configuration gives the same names.
class FieldParts {
public:
    /// `reserved`: parts already taken in this scope.
    explicit FieldParts(std::unordered_set<std::string> reserved = {});
    /// The part for `name` (field_part), made unique; never empty (`_` for an empty name).
    std::string unique(std::string_view name);

private:
    std::unordered_set<std::string> taken_;
};

/// `text` as a Lua 5.2 string literal in double quotes: printable ASCII as it is, `"` and `\`
/// escaped, every other byte (control characters, UTF-8 sequences) as `\ddd`, so the generated
/// file is ASCII whatever the names.
std::string lua_string(std::string_view text);

}  // namespace eip2mqtt::app::dissector
