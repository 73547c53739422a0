#include "eip2mqtt/core/config/diagnostic.hpp"

#include <mutex>
#include <ostream>
#include <set>

namespace eip2mqtt::core::config {

FileName::FileName(std::string_view name) {
    if (name.empty()) return;
    // A node-based set: interned strings never move, and are never freed.
    static std::mutex lock;
    static std::set<std::string, std::less<>> names;
    const std::lock_guard guard(lock);
    auto it = names.find(name);
    if (it == names.end()) it = names.emplace(name).first;
    name_ = &*it;
}

const std::string& FileName::str() const {
    static const std::string none;
    return name_ ? *name_ : none;
}

std::ostream& operator<<(std::ostream& out, const FileName& name) { return out << name.str(); }

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
