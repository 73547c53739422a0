#include "eip2mqtt/core/net/subnet.hpp"

#include <algorithm>
#include <charconv>

#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::net {
namespace {

std::uint32_t mask_of(std::uint8_t prefix) {
    return prefix == 0 ? 0 : ~std::uint32_t{0} << (32 - prefix);
}

}  // namespace

bool Subnet::contains(std::uint32_t ip) const { return (ip & mask_of(prefix)) == address; }

std::optional<Subnet> parse_subnet(std::string_view text) {
    const auto slash = text.find('/');
    const auto address_text = text.substr(0, slash);
    // A dotted address only: the producer-id parser's decimal form is no notation for a host.
    if (std::count(address_text.begin(), address_text.end(), '.') != 3) return std::nullopt;
    const auto address = wire::parse_producer_id(address_text);
    if (!address) return std::nullopt;
    unsigned prefix = 32;
    if (slash != std::string_view::npos) {
        const auto digits = text.substr(slash + 1);
        const auto [end, ec] =
            std::from_chars(digits.data(), digits.data() + digits.size(), prefix);
        if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size() ||
            prefix > 32) {
            return std::nullopt;
        }
    }
    const auto bits = static_cast<std::uint8_t>(prefix);
    return Subnet{address->value & mask_of(bits), bits};
}

std::string to_string(const Subnet& subnet) {
    return wire::to_string(wire::ProducerId{subnet.address}) + "/" + std::to_string(subnet.prefix);
}

bool allowed(std::span<const Subnet> subnets, std::uint32_t ip) {
    return std::any_of(subnets.begin(), subnets.end(),
                       [&](const Subnet& subnet) { return subnet.contains(ip); });
}

}  // namespace eip2mqtt::core::net
