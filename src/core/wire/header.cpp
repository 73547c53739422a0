#include "eip2mqtt/core/wire/header.hpp"

#include "core/detail/parse_decimal.hpp"

namespace eip2mqtt::core::wire {

using core::detail::parse_decimal;

std::optional<ProducerId> parse_producer_id(std::string_view text) {
    if (text.find('.') == std::string_view::npos) {
        // GE's "decimal" form: the 4 wire bytes read as a little-endian u32.
        std::uint32_t le = 0;
        if (!parse_decimal(text, le)) return std::nullopt;
        const std::uint32_t dotted =
            (le & 0xFF) << 24 | (le >> 8 & 0xFF) << 16 | (le >> 16 & 0xFF) << 8 | (le >> 24 & 0xFF);
        return ProducerId{dotted};
    }
    std::uint32_t value = 0;
    std::size_t start = 0;
    for (int i = 0; i < 4; ++i) {
        const auto dot = text.find('.', start);
        if ((i < 3) == (dot == std::string_view::npos)) return std::nullopt;
        unsigned octet = 0;
        if (!parse_decimal(text.substr(start, dot - start), octet) || octet > 255) {
            return std::nullopt;
        }
        value = value << 8 | octet;
        start = dot + 1;
    }
    return ProducerId{value};
}

std::string to_string(ProducerId id) {
    return std::to_string(id.value >> 24) + "." + std::to_string(id.value >> 16 & 0xFF) + "." +
           std::to_string(id.value >> 8 & 0xFF) + "." + std::to_string(id.value & 0xFF);
}

std::optional<Signature> parse_signature(std::string_view text) {
    const auto dot = text.find('.');
    unsigned major = 0;
    unsigned minor = 0;
    if (!parse_decimal(text.substr(0, dot), major) || major > 255) return std::nullopt;
    if (dot != std::string_view::npos &&
        (!parse_decimal(text.substr(dot + 1), minor) || minor > 255)) {
        return std::nullopt;
    }
    return Signature{static_cast<std::uint8_t>(major), static_cast<std::uint8_t>(minor)};
}

std::string to_string(Signature signature) {
    return std::to_string(signature.major) + "." + std::to_string(signature.minor);
}

}  // namespace eip2mqtt::core::wire
