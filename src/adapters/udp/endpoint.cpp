#include "eip2mqtt/adapters/udp/endpoint.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>

#include <charconv>
#include <cstring>

namespace eip2mqtt::adapters::udp {

std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
    const std::string copy(text);
    in_addr addr{};
    if (inet_pton(AF_INET, copy.c_str(), &addr) != 1) return std::nullopt;
    return ntohl(addr.s_addr);
}

std::optional<Endpoint> resolve_endpoint(std::string_view text, std::uint16_t default_port) {
    Endpoint endpoint;
    endpoint.port = default_port;
    std::string_view host = text;
    if (const auto colon = text.rfind(':'); colon != std::string_view::npos) {
        host = text.substr(0, colon);
        const auto port_text = text.substr(colon + 1);
        unsigned port = 0;
        const auto [end, ec] =
            std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
        if (ec != std::errc{} || end != port_text.data() + port_text.size() || port == 0 ||
            port > 65535) {
            return std::nullopt;
        }
        endpoint.port = static_cast<std::uint16_t>(port);
    }
    if (host.empty()) return std::nullopt;
    if (auto address = parse_ipv4(host)) {
        endpoint.address = *address;
        return endpoint;
    }
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_DGRAM;
    addrinfo* result = nullptr;
    const std::string host_copy(host);
    if (getaddrinfo(host_copy.c_str(), nullptr, &hints, &result) != 0 || result == nullptr) {
        return std::nullopt;
    }
    sockaddr_in sin{};
    std::memcpy(&sin, result->ai_addr, sizeof sin);
    freeaddrinfo(result);
    endpoint.address = ntohl(sin.sin_addr.s_addr);
    return endpoint;
}

std::string ipv4_to_string(std::uint32_t address) {
    return std::to_string(address >> 24) + "." + std::to_string(address >> 16 & 0xFF) + "." +
           std::to_string(address >> 8 & 0xFF) + "." + std::to_string(address & 0xFF);
}

std::string to_string(const Endpoint& endpoint) {
    return ipv4_to_string(endpoint.address) + ":" + std::to_string(endpoint.port);
}

}  // namespace eip2mqtt::adapters::udp
