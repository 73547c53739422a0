#include "adapters/yaml/detail/scalar_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

#include "eip2mqtt/core/edit_distance.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml::detail {
std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::optional<std::string_view> suggestion(std::string_view key, Keys allowed) {
    std::optional<std::string_view> best;
    std::size_t best_distance = 3;  // at most 2 edits
    const std::string key_lower = lower(key);
    for (const auto candidate : allowed) {
        const auto distance = core::edit_distance(key_lower, candidate);
        if (distance < best_distance && distance < candidate.size()) {
            best = candidate;
            best_distance = distance;
        }
    }
    return best;
}

std::optional<double> parse_double(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty() ||
        !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
    if (std::count(text.begin(), text.end(), '.') != 3) return std::nullopt;
    const auto id = core::wire::parse_producer_id(text);
    if (!id) return std::nullopt;
    return id->value;
}

bool valid_host_port(std::string_view text, bool port_required) {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos) return !port_required && !text.empty();
    const auto port = parse_integer<unsigned>(text.substr(colon + 1));
    return colon > 0 && port && *port >= 1 && *port <= 65535;
}

bool one_host_port(std::string_view text) {
    return std::none_of(text.begin(), text.end(), [](char c) {
        const auto byte = static_cast<unsigned char>(c);
        return c == ',' || byte <= 0x20 || byte == 0x7F;
    });
}

}  // namespace eip2mqtt::adapters::yaml::detail
