#include "eip2mqtt/core/plan/address.hpp"

#include "core/detail/parse_decimal.hpp"

namespace eip2mqtt::core::plan {

using core::detail::parse_decimal;

std::optional<Address> parse_address(std::string_view text) {
    Address address;
    const auto dot = text.find('.');
    if (!parse_decimal(text.substr(0, dot), address.byte)) return std::nullopt;
    if (dot == std::string_view::npos) return address;
    unsigned bit = 0;
    if (!parse_decimal(text.substr(dot + 1), bit) || bit > 7) return std::nullopt;
    address.bit = static_cast<std::uint8_t>(bit);
    return address;
}

std::string to_string(const Address& address) {
    return std::to_string(address.byte) + "." + std::to_string(address.bit);
}

}  // namespace eip2mqtt::core::plan
