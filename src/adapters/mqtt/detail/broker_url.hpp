#pragma once
/// The host and port a broker URL names, for what Paho does not tell: which TCP socket is the
/// broker's (TCP_NODELAY, see tcp_nodelay.hpp) and whether the connection uses TLS.
///
/// Module-private (src/adapters/mqtt/detail).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace eip2mqtt::adapters::mqtt::detail {

struct BrokerEndpoint {
    std::string host;
    std::uint16_t port = 0;
    bool tls = false;  ///< ssl://, mqtts:// or wss://
};

/// scheme://host[:port][/path]; host may be a bracketed IPv6 address. The port defaults by
/// scheme (1883, 8883 for TLS, 80 for ws://, 443 for wss://). nullopt: not such a URL.
std::optional<BrokerEndpoint> parse_broker_url(const std::string& url);

/// The broker tried after broker `current` of a list of `count` (ClientOptions::urls): the next
/// one, the first after the last.
constexpr std::size_t next_broker(std::size_t current, std::size_t count) {
    return count == 0 ? 0 : (current + 1) % count;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
