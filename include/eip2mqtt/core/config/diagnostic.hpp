#pragma once
/// Configuration errors, with where they are: checks collect them all rather than stop.

#include <compare>
#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::core::config {

/// The name of a configuration file, shared by every Mark made in it: a path is longer than
/// std::string's inline buffer, and a configuration of 100,000 tags or point-list rows holds a
/// mark for each: a heap copy per mark weighed on start-up (see
/// docs/decisions/0001-configurations-of-100000-tags.md). Names are interned for the life of the
/// process (a gateway reads a handful of files), so a copy is a pointer.
///
/// Threading: any; interning takes a lock, reading does not.
class FileName {
public:
    FileName() = default;
    FileName(std::string_view name);  // NOLINT(google-explicit-constructor): a name is a file name
    FileName(const std::string& name) : FileName(std::string_view(name)) {}  // NOLINT: as above
    FileName(const char* name) : FileName(std::string_view(name)) {}         // NOLINT: as above

    const std::string& str() const;
    operator const std::string&() const { return str(); }  // NOLINT: reads as its string
    bool empty() const { return name_ == nullptr; }

    /// Interned: equal names are one string.
    friend bool operator==(const FileName& a, const FileName& b) { return a.name_ == b.name_; }
    friend std::strong_ordering operator<=>(const FileName& a, const FileName& b) {
        return a.str() <=> b.str();
    }
    friend std::ostream& operator<<(std::ostream& out, const FileName& name);

private:
    const std::string* name_ = nullptr;  ///< interned; null: no file
};

/// A position in a configuration file; line and column are 1-based, 0 when unknown.
struct Mark {
    FileName file;
    int line = 0;
    int column = 0;
};

struct Diagnostic {
    Mark mark;
    std::string message;

    /// `file:line:column: error: message`.
    std::string to_string() const;
};

using Diagnostics = std::vector<Diagnostic>;

/// `text` in single quotes, fit for a one-line message: what a broker would refuse in text
/// (control characters, NUL included, invalid UTF-8, non-characters; plan::text_problem) is
/// escaped as `\0`, `\t`, `\n`, `\r`, `\xHH` (a byte) or `\uHHHH` (a character), so a name
/// that holds an escape sequence cannot drive the terminal that shows the message; text longer
/// than max_in_quotes_bytes is cut there and followed by its length: `'AAAA...' (70000 bytes)`.
std::string in_quotes(std::string_view text);

inline constexpr std::size_t max_in_quotes_bytes = 120;

}  // namespace eip2mqtt::core::config
