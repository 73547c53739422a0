#include "adapters/yaml/detail/skeleton_lines.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

namespace exchange = core::exchange;
namespace wire = core::wire;

std::string ipv4(std::uint32_t address) { return wire::to_string(wire::ProducerId{address}); }

}  // namespace

void item_head(const wire::ExchangeKey& key, std::string& out) {
    const auto producer = wire::to_string(key.producer_id);
    const auto id = std::to_string(key.exchange_id);
    out += "  - name: \"" + producer + "-" + id + "\"\n";
    out += "    direction: consume\n";
    out += "    producer_id: " + producer + "\n";
    out += "    exchange_id: " + id + "\n";
}

std::string destination_text(exchange::DestinationKind kind, std::uint32_t address) {
    switch (kind) {
        case exchange::DestinationKind::unicast:
            return "unicast to " + ipv4(address);
        case exchange::DestinationKind::broadcast:
            return "broadcast to " + ipv4(address);
        case exchange::DestinationKind::multicast:
            return "multicast group " + ipv4(address) +
                   " (the gateway joins it with eip.multicast: [ { group: " + ipv4(address) +
                   " } ])";
        case exchange::DestinationKind::unknown:
            break;
    }
    return "unknown";
}

}  // namespace eip2mqtt::adapters::yaml::detail
