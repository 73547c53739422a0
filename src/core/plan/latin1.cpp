#include "eip2mqtt/core/plan/latin1.hpp"

#include <cstdint>

namespace eip2mqtt::core::plan {

std::string latin1_to_utf8(std::span<const std::byte> bytes, bool trim) {
    std::size_t end = bytes.size();
    if (trim) {
        while (end > 0 && (bytes[end - 1] == std::byte{0} || bytes[end - 1] == std::byte{' '})) {
            --end;
        }
    }
    std::string out;
    out.reserve(end);
    for (std::size_t i = 0; i < end; ++i) {
        const auto code = std::to_integer<unsigned>(bytes[i]);
        if (code < 0x80) {
            out += static_cast<char>(code);
        } else {
            out += static_cast<char>(0xC0 | code >> 6);
            out += static_cast<char>(0x80 | (code & 0x3F));
        }
    }
    return out;
}

std::optional<std::string> utf8_to_latin1(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto lead = static_cast<std::uint8_t>(text[i]);
        if (lead < 0x80) {
            out += static_cast<char>(lead);
            continue;
        }
        // Only the two-byte forms of U+0080..U+00FF (lead 0xC2 or 0xC3) have a Latin-1 byte;
        // 0xC0 and 0xC1 would be overlong forms, anything else is beyond U+00FF or no UTF-8.
        if ((lead != 0xC2 && lead != 0xC3) || i + 1 >= text.size()) return std::nullopt;
        const auto next = static_cast<std::uint8_t>(text[i + 1]);
        if ((next & 0xC0) != 0x80) return std::nullopt;
        out += static_cast<char>((lead & 0x03) << 6 | (next & 0x3F));
        ++i;
    }
    return out;
}

}  // namespace eip2mqtt::core::plan
