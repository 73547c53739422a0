#pragma once
/// Configuration errors, with where they are: checks collect them all rather than stop.

#include <string>
#include <vector>

namespace eip2mqtt::core::config {

/// A position in a configuration file; line and column are 1-based, 0 when unknown.
struct Mark {
    std::string file;
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

}  // namespace eip2mqtt::core::config
