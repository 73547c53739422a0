#include "eip2mqtt/core/config/diagnostic.hpp"

namespace eip2mqtt::core::config {

std::string Diagnostic::to_string() const {
    // Compiler-style location, so editors jump to it; unknown parts (0) are left out, and a
    // column means nothing without its line.
    std::string out = mark.file;
    if (mark.line > 0) {
        if (!out.empty()) out += ':';
        out += std::to_string(mark.line);
        if (mark.column > 0) out += ':' + std::to_string(mark.column);
    }
    if (!out.empty()) out += ": ";
    out += "error: ";
    out += message;
    return out;
}

}  // namespace eip2mqtt::core::config
