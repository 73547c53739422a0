#include "eip2mqtt/core/plan/topic_rules.hpp"

#include <cstdint>

namespace eip2mqtt::core::plan {
namespace {

/// Unicode's explicit directional formatting characters (UAX #9 §2): ALM, LRM, RLM, the
/// embeddings and overrides LRE..RLO (U+202E, RIGHT-TO-LEFT OVERRIDE, among them) and the
/// isolates LRI..PDI. Shown, they reorder the text around them ("Trojan Source",
/// CVE-2021-42574): a topic that reads as another, a name that reads as another's.
constexpr bool bidirectional_control(std::uint32_t code) {
    return code == 0x061C || code == 0x200E || code == 0x200F ||
           (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069);
}

}  // namespace

std::string_view text_problem(std::string_view text) {
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const auto* const end = p + text.size();
    while (p < end) {
        const unsigned char lead = *p;
        std::uint32_t code = 0;
        std::size_t length = 0;
        if (lead < 0x80) {
            code = lead;
            length = 1;
        } else if ((lead & 0xE0) == 0xC0) {
            code = lead & 0x1Fu;
            length = 2;
        } else if ((lead & 0xF0) == 0xE0) {
            code = lead & 0x0Fu;
            length = 3;
        } else if ((lead & 0xF8) == 0xF0) {
            code = lead & 0x07u;
            length = 4;
        } else {
            return "is not valid UTF-8";
        }
        if (static_cast<std::size_t>(end - p) < length) return "is not valid UTF-8";
        for (std::size_t i = 1; i < length; ++i) {
            if ((p[i] & 0xC0) != 0x80) return "is not valid UTF-8";
            code = (code << 6) | (p[i] & 0x3Fu);
        }
        static constexpr std::uint32_t shortest_of_length[] = {0, 0, 0x80, 0x800, 0x10000};
        if (code < shortest_of_length[length] || code > 0x10FFFF) return "is not valid UTF-8";
        if (code >= 0xD800 && code <= 0xDFFF) return "is not valid UTF-8";
        if (code == 0) return "contains a NUL character";
        if (code <= 0x1F || (code >= 0x7F && code <= 0x9F)) return "contains a control character";
        if ((code >= 0xFDD0 && code <= 0xFDEF) || (code & 0xFFFEu) == 0xFFFEu) {
            return "contains a Unicode non-character";
        }
        if (bidirectional_control(code)) {
            return "contains a bidirectional control character (text would read other than it "
                   "is stored)";
        }
        p += length;
    }
    return {};
}

std::string topic_name_problem(std::string_view topic) {
    if (topic.empty()) return "is empty";
    if (topic.size() > max_topic_bytes) {
        return "is " + std::to_string(topic.size()) + " bytes long (MQTT allows " +
               std::to_string(max_topic_bytes) + ")";
    }
    if (topic.find_first_of("+#") != std::string_view::npos) {
        return "contains a wildcard ('+' or '#')";
    }
    return std::string(text_problem(topic));
}

}  // namespace eip2mqtt::core::plan
