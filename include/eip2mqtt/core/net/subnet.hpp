#pragma once
/// An IPv4 subnet in CIDR notation, for `eip.commands.allow`: the requesters the responder
/// answers.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace eip2mqtt::core::net {

struct Subnet {
    std::uint32_t address = 0;  ///< host byte order, first octet high; host bits cleared
    std::uint8_t prefix = 32;   ///< 0..32

    bool contains(std::uint32_t ip) const;
    friend bool operator==(const Subnet&, const Subnet&) = default;
};

/// Parses `a.b.c.d/n` (n 0..32) or `a.b.c.d` (a /32); host bits are cleared, so
/// `10.20.0.7/24` is 10.20.0.0/24. nullopt otherwise.
std::optional<Subnet> parse_subnet(std::string_view text);
std::string to_string(const Subnet& subnet);

/// Whether any of `subnets` contains `ip`.
bool allowed(std::span<const Subnet> subnets, std::uint32_t ip);

}  // namespace eip2mqtt::core::net
