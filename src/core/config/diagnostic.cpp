#include "eip2mqtt/core/config/diagnostic.hpp"

#include <cstdint>
#include <mutex>
#include <ostream>
#include <set>

#include "eip2mqtt/core/plan/topic_rules.hpp"

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

namespace {

void append_hex(std::string& out, std::string_view prefix, std::uint32_t value, int digits) {
    static constexpr char hex[] = "0123456789ABCDEF";
    out += prefix;
    for (int shift = 4 * (digits - 1); shift >= 0; shift -= 4) out += hex[(value >> shift) & 0xF];
}

/// Appends `text` with what text_problem() refuses escaped, one character or byte at a time.
void append_escaped(std::string& out, std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto lead = static_cast<unsigned char>(text[i]);
        std::size_t length = 1;
        if ((lead & 0xE0) == 0xC0) {
            length = 2;
        } else if ((lead & 0xF0) == 0xE0) {
            length = 3;
        } else if ((lead & 0xF8) == 0xF0) {
            length = 4;
        }
        if (length > text.size() - i) length = 1;  // cut short: its lead byte alone is shown
        const auto one = text.substr(i, length);
        if (plan::text_problem(one).empty()) {
            out += one;
            i += length;
            continue;
        }
        if (length == 1) {
            // NUL as \x00, not \0: followed by digits, "\0" reads as another byte ("\012").
            const char* const named = lead == '\t'   ? "\\t"
                                      : lead == '\n' ? "\\n"
                                      : lead == '\r' ? "\\r"
                                                     : nullptr;
            if (named != nullptr) {
                out += named;
            } else {
                append_hex(out, "\\x", lead, 2);
            }
            ++i;
            continue;
        }
        // A well-formed sequence is a refused character (U+0085, U+FFFF...): shown as one;
        // anything else is invalid UTF-8, shown byte by byte.
        std::uint32_t code = lead & (0x7Fu >> length);
        bool well_formed = true;
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(one[k]);
            well_formed = well_formed && (next & 0xC0) == 0x80;
            code = (code << 6) | (next & 0x3Fu);
        }
        static constexpr std::uint32_t shortest[] = {0, 0, 0x80, 0x800, 0x10000};
        well_formed = well_formed && code >= shortest[length] && code <= 0x10FFFF &&
                      (code < 0xD800 || code > 0xDFFF);
        if (well_formed) {
            if (code > 0xFFFF) {
                append_hex(out, "\\U", code, 8);
            } else {
                append_hex(out, "\\u", code, 4);
            }
            i += length;
        } else {
            append_hex(out, "\\x", lead, 2);
            ++i;
        }
    }
}

}  // namespace

std::string in_quotes(std::string_view text) {
    std::string_view shown = text;
    if (text.size() > max_in_quotes_bytes) {
        // Cut before a character, not inside one (a UTF-8 sequence has at most 3 continuations).
        std::size_t end = max_in_quotes_bytes;
        for (int back = 0; back < 3 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80;
             ++back) {
            --end;
        }
        shown = text.substr(0, end);
    }
    std::string out = "'";
    if (plan::text_problem(shown).empty()) {
        out += shown;
    } else {
        append_escaped(out, shown);
    }
    if (shown.size() < text.size()) {
        out += "...' (" + std::to_string(text.size()) + " bytes)";
    } else {
        out += "'";
    }
    return out;
}

}  // namespace eip2mqtt::core::config
