// The walks over a NodeView and the check families of sparkplug_checks.hpp.

#include "tests/conformance/sparkplug_checks.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

namespace eip2mqtt::test::conformance::checks {

std::string where(const NodeConnection& connection, std::size_t packet) {
    const auto& p = connection.packets.at(packet).packet;
    return "connection " + std::to_string(connection.connection) + " (broker " +
           std::to_string(connection.relay) + "), packet " + std::to_string(packet) + " (" +
           (p.topic.empty() ? "type " + std::to_string(static_cast<int>(p.type)) : p.topic) + ")";
}

std::string type_of(const NodeView& view, const NodePacket& packet) {
    if (packet.packet.type != PacketType::publish) return {};
    return view.type_of(packet.packet.topic);
}

bool is_data(std::string_view type) { return type == "NDATA" || type == "DDATA"; }

std::string device_of(const NodeView& view, const std::string& topic_name) {
    const auto type = view.type_of(topic_name);
    if (type.empty()) return {};
    const auto base = view.topic(type);
    if (topic_name.size() <= base.size() + 1) return {};
    return topic_name.substr(base.size() + 1);
}

Verdict each_sent(const NodeView& view, std::string_view type,
                  const std::function<Verdict(const NodeConnection&, std::size_t)>& f) {
    for (const auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto& p = c.packets[i];
            if (!p.from_node || p.packet.type != PacketType::publish) continue;
            const auto t = view.type_of(p.packet.topic);
            if (t.empty() || (!type.empty() && t != type)) continue;
            if (auto verdict = f(c, i)) return verdict;
        }
    }
    return std::nullopt;
}

NodePacket& first_sent(NodeView& view, std::string_view type) {
    for (auto& c : view.connections) {
        for (auto& p : c.packets) {
            const auto t = type_of(view, p);
            const bool wanted = type.empty() ? !t.empty() && t != "NDEATH" : t == type;
            if (p.from_node && wanted) return p;
        }
    }
    throw std::runtime_error("the view has no " + std::string(type) + " to alter");
}

std::optional<State> state_of(const NodePacket& packet) {
    if (packet.from_node || packet.packet.type != PacketType::publish) return std::nullopt;
    const std::string prefix = "spBv1.0/STATE/";
    if (!packet.packet.topic.starts_with(prefix)) return std::nullopt;
    State state;
    state.host = packet.packet.topic.substr(prefix.size());
    const auto json = nlohmann::json::parse(packet.packet.payload, nullptr, false);
    if (!json.is_object() || !json.contains("online") || !json["online"].is_boolean() ||
        !json.contains("timestamp") || !json["timestamp"].is_number_integer()) {
        return std::nullopt;
    }
    state.online = json["online"].get<bool>();
    state.timestamp = json["timestamp"].get<std::int64_t>();
    return state;
}

bool is_rebirth_request(const NodeView& view, const NodePacket& packet) {
    if (packet.from_node || type_of(view, packet) != "NCMD" || !packet.payload) return false;
    for (const auto& m : packet.payload->metrics()) {
        if (m.name() == "Node Control/Rebirth" && m.has_boolean_value() && m.boolean_value()) {
            return true;
        }
    }
    return false;
}

Requirement qos0_not_retained(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    return {tck_id, Run::mqtt5,
            [t](const NodeView& view) {
                return each_sent(view, t, [](const NodeConnection& c, std::size_t i) -> Verdict {
                    const auto& p = c.packets[i].packet;
                    if (p.qos == 0 && !p.retain) return std::nullopt;
                    return where(c, i) + ": QoS " + std::to_string(p.qos) +
                           (p.retain ? ", retained" : "");
                });
            },
            [t](NodeView& view) { first_sent(view, t).packet.qos = 1; }};
}

Requirement topic_of_type(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    const bool device = t.front() == 'D';
    return {tck_id, Run::mqtt5,
            [t, device](const NodeView& view) -> Verdict {
                const auto sent = each_sent(view, t, [&](const NodeConnection& c, std::size_t i) {
                    const auto d = device_of(view, c.packets[i].packet.topic);
                    if (d.empty() != device) return Verdict{};
                    return Verdict{where(c, i) +
                                   (device ? ": no device element" : ": a device element")};
                });
                if (sent) return sent;
                // A check of a type never sent would hold for want of looking.
                const auto found = each_sent(
                    view, t, [](const NodeConnection&, std::size_t) { return Verdict{"found"}; });
                return found ? Verdict{} : Verdict{"no " + t + " was published in the run"};
            },
            [t, device](NodeView& view) {
                auto& topic_name = first_sent(view, t).packet.topic;
                if (device) {
                    topic_name = topic_name.substr(0, topic_name.rfind('/'));
                } else {
                    topic_name += "/extra";
                }
            }};
}

}  // namespace eip2mqtt::test::conformance::checks
