#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::core {

namespace {

std::string escaped(std::string_view text, std::size_t max_bytes, bool ascii) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string out;
    out.reserve(std::min(text.size(), max_bytes) + 3);
    for (const char c : text.substr(0, max_bytes)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7F || (ascii && byte >= 0x80)) {
            out += "\\x";
            out += hex[byte >> 4];
            out += hex[byte & 0xF];
        } else {
            out += c;
        }
    }
    if (text.size() > max_bytes) out += "...";
    return out;
}

}  // namespace

std::string printable(std::string_view text, std::size_t max_bytes) {
    return escaped(text, max_bytes, false);
}

std::string printable_ascii(std::string_view text, std::size_t max_bytes) {
    return escaped(text, max_bytes, true);
}

}  // namespace eip2mqtt::core
