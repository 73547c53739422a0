#include "eip2mqtt/app/cli/dissector/field_names.hpp"

#include <cstdio>
#include <utility>

namespace eip2mqtt::app::dissector {
namespace {

bool allowed_in_field(unsigned char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
}

bool utf8_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

}  // namespace

std::string field_part(std::string_view name) {
    std::string part;
    part.reserve(name.size());
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (allowed_in_field(c)) {
            part += ch;
        } else if (!utf8_continuation(c)) {
            part += '_';
        }
    }
    return part;
}

FieldParts::FieldParts(std::unordered_set<std::string> reserved) : taken_(std::move(reserved)) {}

std::string FieldParts::unique(std::string_view name) {
    std::string base = field_part(name);
    if (base.empty()) base = "_";
    std::string part = base;
    for (int n = 2; taken_.contains(part); ++n) part = base + "_" + std::to_string(n);
    taken_.insert(part);
    return part;
}

std::string lua_string(std::string_view text) {
    std::string literal = "\"";
    literal.reserve(text.size() + 2);
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') {
            literal += '\\';
            literal += ch;
        } else if (c >= 0x20 && c < 0x7F) {
            literal += ch;
        } else {
            // Three digits always: a digit that follows cannot extend the escape.
            char escape[5];
            std::snprintf(escape, sizeof escape, "\\%03u", static_cast<unsigned>(c));
            literal += escape;
        }
    }
    literal += '"';
    return literal;
}

}  // namespace eip2mqtt::app::dissector
