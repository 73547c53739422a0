#include "eip2mqtt/adapters/yaml/discovered_skeleton.hpp"

#include <algorithm>
#include <set>
#include <string_view>

#include "adapters/yaml/detail/skeleton_lines.hpp"
#include "eip2mqtt/adapters/yaml/skeleton.hpp"
#include "eip2mqtt/core/printable.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml {
namespace {

namespace command = core::command;
namespace exchange = core::exchange;
namespace wire = core::wire;

using command::DestinationType;
using command::ExchangeConfig;
using command::ExchangeMode;

// The length the validation accepts (config.cpp).
constexpr std::uint16_t max_length = 1400;

// What a node told (a NAK's text...), as it may stand in a comment line: no line break, no
// byte that would end the comment.
std::string told(std::string_view text) { return core::printable_ascii(text, 400); }

std::string key_text(const wire::ExchangeKey& key) {
    return wire::to_string(key.producer_id) + "/" + std::to_string(key.exchange_id);
}

void length_line(const ExchangeConfig& c, std::string& out) {
    if (c.length == 0 || c.length > max_length) {
        out += "    length: " + std::string(c.length == 0 ? "1" : "1400") + "  # TODO: the node " +
               "told " + std::to_string(c.length) + " bytes; a length is 1 to 1400\n";
        return;
    }
    out += "    length: " + std::to_string(c.length) + "  # data bytes, as the node told\n";
}

void signature_line(const ExchangeConfig& c, std::string& out) {
    const auto signature = wire::Signature::from_wire(c.signature);
    if (signature.is_set()) {
        out += "    signature: \"" + wire::to_string(signature) + "\"\n";
    } else {
        out += "    # signature: none (the node has 0.0)\n";
    }
}

void period_line(const ExchangeConfig& c, std::string& out) {
    if (c.period_ms == 0) {
        out +=
            "    period_ms: 1000  # TODO: the node told 0 (an exchange only for commands, "
            "never produced); the default\n";
        return;
    }
    const auto period = std::clamp(c.period_ms, detail::min_period_ms, detail::max_period_ms);
    out += "    period_ms: " + std::to_string(period) + "  # as the node told";
    if (period != c.period_ms) out += " (" + std::to_string(c.period_ms) + "; 2 to 3600000)";
    out += "\n";
}

exchange::DestinationKind kind_of(DestinationType type) {
    switch (type) {
        case DestinationType::unicast:
            return exchange::DestinationKind::unicast;
        case DestinationType::broadcast:
            return exchange::DestinationKind::broadcast;
        case DestinationType::multicast:
            return exchange::DestinationKind::multicast;
        default:
            return exchange::DestinationKind::unknown;
    }
}

void destination_line(const ExchangeConfig& c, std::string& out) {
    out += "    # destination: ";
    const auto kind = kind_of(c.destination_type);
    out += kind == exchange::DestinationKind::unknown
               ? "none told"
               : detail::destination_text(kind, c.destination);
    out += ", port " + std::to_string(c.port);
    if (c.port != wire::default_port) out += " (the gateway receives on eip.port)";
    out += "\n";
}

void exchange_item(const DiscoveredNode& node, const ExchangeConfig& c, std::string& out) {
    detail::item_head(c.key, out);
    length_line(c, out);
    signature_line(c, out);
    period_line(c, out);
    out += "    topic: \"" + skeleton_topic(c.key) + "\"  # under base_topic\n";
    destination_line(c, out);
    out += "    # told by " + node.address + ": state " +
           (c.state == command::ExchangeState::active ? "active" : "idle") + "\n";
    out += "    tags: []  # TODO: the byte map; until then only {topic}/_status is published\n";
}

// What gets no skeleton, as comment lines.
std::string notes(std::span<const DiscoveredNode> nodes) {
    std::string out;
    for (const auto& node : nodes) {
        if (!node.problem.empty()) {
            out += "# " + node.address + ": " + told(node.problem) + "\n";
            continue;
        }
        for (const auto& e : node.exchanges) {
            if (!e.config) {
                out += "# " + key_text(e.cell.key) + " (" + node.address +
                       "): not retrieved: " + told(e.problem) + "\n";
            } else if (e.config->mode == ExchangeMode::consumed) {
                out += "# " + key_text(e.cell.key) + ": consumed by " + node.address + " (" +
                       std::to_string(e.config->length) + " bytes every " +
                       std::to_string(e.config->period_ms) +
                       " ms): no skeleton; producing it "
                       "would overwrite what the node reads\n";
            }
        }
        if (node.exchanges.size() < node.total) {
            out += "# " + node.address + ": " + std::to_string(node.total - node.exchanges.size()) +
                   " of its " + std::to_string(node.total) +
                   " exchanges could not be listed (the Summary index is one byte)\n";
        }
    }
    return out;
}

}  // namespace

std::string discovered_skeleton(std::span<const DiscoveredNode> nodes) {
    std::string items;
    std::set<wire::ExchangeKey> seen;
    std::size_t count = 0;
    for (const auto& node : nodes) {
        for (const auto& e : node.exchanges) {
            if (!e.config || e.config->mode == ExchangeMode::consumed) continue;
            if (!seen.insert(e.config->key).second) continue;
            exchange_item(node, *e.config, items);
            ++count;
        }
    }
    std::string out = "# discover --yaml: " + std::to_string(count) +
                      (count == 1 ? " exchange" : " exchanges") +
                      " the nodes produce. Rename at will; add tags where the byte map is known.\n";
    out += notes(nodes);
    if (count > 0) out += "exchanges:\n" + items;
    return out;
}

}  // namespace eip2mqtt::adapters::yaml
