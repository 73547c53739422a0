#pragma once
/// IPv4 endpoints as the UDP adapters use them: `host` or `host:port` from configuration,
/// resolved once.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace eip2mqtt::adapters::udp {

struct Endpoint {
    std::uint32_t address = 0;  ///< IPv4, host byte order
    std::uint16_t port = 0;
};

/// Parses `a.b.c.d`, `a.b.c.d:port` or `name[:port]` (resolved with getaddrinfo, IPv4 only);
/// `default_port` when no port is given. nullopt when it does not resolve.
std::optional<Endpoint> resolve_endpoint(std::string_view text, std::uint16_t default_port);

/// Parses a dotted IPv4 address; nullopt otherwise.
std::optional<std::uint32_t> parse_ipv4(std::string_view text);

std::string to_string(const Endpoint& endpoint);
std::string ipv4_to_string(std::uint32_t address);

}  // namespace eip2mqtt::adapters::udp
