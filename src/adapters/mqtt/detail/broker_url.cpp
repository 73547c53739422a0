#include "adapters/mqtt/detail/broker_url.hpp"

#include <exception>

namespace eip2mqtt::adapters::mqtt::detail {

std::optional<BrokerEndpoint> parse_broker_url(const std::string& url) {
    const auto sep = url.find("://");
    if (sep == std::string::npos) {
        return std::nullopt;
    }
    const std::string scheme = url.substr(0, sep);
    BrokerEndpoint ep;
    ep.tls = scheme == "ssl" || scheme == "mqtts" || scheme == "wss";
    ep.port = scheme == "ws" ? 80 : scheme == "wss" ? 443 : ep.tls ? 8883 : 1883;
    std::string rest = url.substr(sep + 3);
    rest = rest.substr(0, rest.find('/'));
    std::string port;
    if (!rest.empty() && rest.front() == '[') {
        const auto close = rest.find(']');
        if (close == std::string::npos) {
            return std::nullopt;
        }
        ep.host = rest.substr(1, close - 1);
        if (close + 1 < rest.size() && rest[close + 1] == ':') {
            port = rest.substr(close + 2);
        }
    } else {
        const auto colon = rest.rfind(':');
        ep.host = rest.substr(0, colon);
        if (colon != std::string::npos) {
            port = rest.substr(colon + 1);
        }
    }
    if (!port.empty()) {
        try {
            const int p = std::stoi(port);
            if (p <= 0 || p > 65535) {
                return std::nullopt;
            }
            ep.port = static_cast<std::uint16_t>(p);
        } catch (const std::exception&) {
            return std::nullopt;
        }
    }
    return ep;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
