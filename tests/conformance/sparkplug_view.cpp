// The node's connections out of the relays' events.

#include "tests/conformance/sparkplug_view.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace eip2mqtt::test::conformance {
namespace {

bool is_node_connect(const MqttPacket& packet) {
    return packet.type == PacketType::connect && packet.client_id.ends_with("-sparkplug");
}

}  // namespace

std::string NodeView::type_of(const std::string& topic_name) const {
    const auto prefix = "spBv1.0/" + group + "/";
    if (!topic_name.starts_with(prefix)) return {};
    const auto rest = topic_name.substr(prefix.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos) return {};
    const auto after = rest.substr(slash + 1);
    if (after != node && !after.starts_with(node + "/")) return {};
    return rest.substr(0, slash);
}

NodeView node_view(const std::vector<RelayEvent>& unordered, std::string group, std::string node) {
    NodeView view;
    view.group = std::move(group);
    view.node = std::move(node);
    auto events = unordered;
    std::stable_sort(events.begin(), events.end(),
                     [](const RelayEvent& a, const RelayEvent& b) { return a.at < b.at; });
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;  // (relay, connection)
    for (const auto& e : events) {
        const auto key = std::make_pair(e.relay, e.connection);
        auto found = index.find(key);
        if (found == index.end()) {
            if (e.closed() || !e.from_client() || !is_node_connect(*e.packet)) continue;
            index.emplace(key, view.connections.size());
            NodeConnection c;
            c.relay = e.relay;
            c.connection = e.connection;
            c.connect = *e.packet;
            c.opened = c.ended = e.at;
            view.connections.push_back(std::move(c));
            continue;
        }
        auto& c = view.connections[found->second];
        if (e.closed()) {
            if (!c.closed) {
                c.closed_by_node = e.from_client();
                c.ended = e.at;
            }
            c.closed = true;
            continue;
        }
        NodePacket p{e.from_client(), *e.packet, std::nullopt, e.at};
        // The node's DISCONNECT ends its session there, whoever closes the socket first.
        if (p.from_node && p.packet.type == PacketType::disconnect && !c.closed) {
            c.closed = c.closed_by_node = true;
            c.ended = e.at;
        }
        if (p.packet.type == PacketType::publish && !view.type_of(p.packet.topic).empty()) {
            SparkplugPayload payload;
            if (payload.ParseFromString(p.packet.payload)) p.payload = std::move(payload);
        }
        c.packets.push_back(std::move(p));
    }
    return view;
}

std::int64_t int_of(const SparkplugPayload::Metric& metric) {
    if (metric.has_int_value()) return static_cast<std::int32_t>(metric.int_value());
    return static_cast<std::int64_t>(metric.long_value());
}

const SparkplugPayload::Metric* metric_named(const SparkplugPayload& payload,
                                             const std::string& name) {
    for (const auto& m : payload.metrics()) {
        if (m.name() == name) return &m;
    }
    return nullptr;
}

}  // namespace eip2mqtt::test::conformance
