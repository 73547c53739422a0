#pragma once
/// Scalars of the configuration as text: numbers spelt as YAML users spell them (`+5`),
/// addresses, and the allowed key closest to a typo.
///
/// Module-private to src/adapters/yaml.

#include <charconv>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace eip2mqtt::adapters::yaml::detail {

using Keys = std::span<const std::string_view>;

/// ASCII lower case (YAML booleans, key suggestions).
std::string lower(std::string_view text);

/// The allowed key closest to `key`, when it is close enough to be a typo.
std::optional<std::string_view> suggestion(std::string_view key, Keys allowed);

/// A whole decimal integer, with an optional leading '+'.
template <class T>
std::optional<T> parse_integer(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return value;
}

/// A finite number, with an optional leading '+'.
std::optional<double> parse_double(std::string_view text);

/// A dotted IPv4 address, host order.
std::optional<std::uint32_t> parse_ipv4(std::string_view text);

/// `host` or `host:port`: the port, when written, must be 1..65535.
bool valid_host_port(std::string_view text, bool port_required);

/// `text` names one address, not a list: no ',' (civetweb's list separator), no space or
/// control character.
bool one_host_port(std::string_view text);

}  // namespace eip2mqtt::adapters::yaml::detail
