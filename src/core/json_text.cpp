#include "eip2mqtt/core/json_text.hpp"

namespace eip2mqtt::core {

void append_json_string(std::string& out, std::string_view text) {
    out += '"';
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            // Escaped as JSON libraries write them, never raw.
            constexpr std::string_view shorts = "\b\t\n\f\r";
            constexpr std::string_view letters = "btnfr";
            if (const auto at = shorts.find(c); at != std::string_view::npos) {
                out += '\\';
                out += letters[at];
            } else {
                static constexpr char hex[] = "0123456789abcdef";
                out += "\\u00";
                out += hex[static_cast<unsigned char>(c) >> 4];
                out += hex[static_cast<unsigned char>(c) & 0xF];
            }
        } else {
            out += c;
        }
    }
    out += '"';
}

}  // namespace eip2mqtt::core
