// The checks of the node's session on a connection: its subscriptions and births after the
// broker's CONNACK, the primary host's STATE before births, what an offline STATE ends, how
// it disconnects, and one broker at a time.

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

/// The index of the first packet of `c` the node sent of `type`, or c.packets.size().
std::size_t first_of(const NodeView& view, const NodeConnection& c, std::string_view type) {
    for (std::size_t i = 0; i < c.packets.size(); ++i) {
        if (c.packets[i].from_node && type_of(view, c.packets[i]) == type) return i;
    }
    return c.packets.size();
}

bool subscribed_before(const NodeConnection& c, std::size_t end, const std::string& filter) {
    for (std::size_t i = 0; i < end && i < c.packets.size(); ++i) {
        const auto& p = c.packets[i];
        if (!p.from_node || p.packet.type != PacketType::subscribe) continue;
        for (const auto& f : p.packet.filters) {
            if (f == filter) return true;
        }
    }
    return false;
}

Verdict subscribed_before_births(const NodeView& view, const std::string& filter) {
    for (const auto& c : view.connections) {
        const auto birth = first_of(view, c, "NBIRTH");
        if (birth == c.packets.size()) continue;
        if (!subscribed_before(c, birth, filter)) {
            return where(c, birth) + ": no SUBSCRIBE to " + filter + " before it";
        }
    }
    return std::nullopt;
}

void drop_subscribe_filter(NodeView& view, const std::string& filter) {
    for (auto& c : view.connections) {
        for (auto& p : c.packets) std::erase(p.packet.filters, filter);
    }
}

}  // namespace

Verdict subscribes_ncmd(const NodeView& view) {
    return subscribed_before_births(view, view.topic("NCMD"));
}
void break_subscribes_ncmd(NodeView& view) { drop_subscribe_filter(view, view.topic("NCMD")); }

Verdict subscribes_dcmd(const NodeView& view) {
    return subscribed_before_births(view, view.topic("DCMD") + "/+");
}
void break_subscribes_dcmd(NodeView& view) {
    drop_subscribe_filter(view, view.topic("DCMD") + "/+");
}

Verdict births_after_connack(const NodeView& view) {
    for (const auto& c : view.connections) {
        bool accepted = false;
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto& p = c.packets[i];
            if (!p.from_node && p.packet.type == PacketType::connack) {
                accepted = p.packet.reason == 0;
            }
            if (p.from_node && !type_of(view, p).empty() && !accepted) {
                return where(c, i) + ": before the broker accepted the connection";
            }
        }
    }
    return std::nullopt;
}
void break_births_after_connack(NodeView& view) {
    for (auto& c : view.connections)
        std::erase_if(c.packets,
                      [](const NodePacket& p) { return p.packet.type == PacketType::connack; });
}

Verdict no_device_before_nbirth(const NodeView& view) {
    for (const auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto t = type_of(view, c.packets[i]);
            if (!c.packets[i].from_node || t.empty() || t == "NDEATH") continue;
            if (t == "NBIRTH") break;
            return where(c, i) + ": before the connection's NBIRTH";
        }
    }
    return std::nullopt;
}
void break_no_device_before_nbirth(NodeView& view) {
    for (auto& c : view.connections) {
        const auto birth = first_of(view, c, "NBIRTH");
        if (birth == c.packets.size()) continue;
        auto early = c.packets[birth];
        early.packet.topic = view.topic("DDATA") + "/line";
        c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(birth), std::move(early));
        return;
    }
}

Verdict ndeath_before_disconnect(const NodeView& view) {
    for (const auto& c : view.connections) {
        bool death = false;
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto& p = c.packets[i];
            if (!p.from_node) continue;
            if (type_of(view, p) == "NDEATH") death = true;
            if (p.packet.type == PacketType::disconnect && !death) {
                return where(c, i) + ": DISCONNECT without an NDEATH before it";
            }
        }
    }
    return std::nullopt;
}
void break_ndeath_before_disconnect(NodeView& view) {
    for (auto& c : view.connections) {
        std::erase_if(c.packets, [&](const NodePacket& p) {
            return p.from_node && type_of(view, p) == "NDEATH";
        });
    }
}

Verdict disconnect_with_will_reason(const NodeView& view) {
    bool any = false;
    for (const auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto& p = c.packets[i];
            if (!p.from_node || p.packet.type != PacketType::disconnect) continue;
            any = true;
            if (c.connect.protocol_level == 5 && p.packet.reason != 0x04) {
                return where(c, i) + ": DISCONNECT reason " +
                       std::to_string(p.packet.reason.value_or(0)) + ", not 0x04";
            }
        }
    }
    return any ? Verdict{} : Verdict{"the node sent no DISCONNECT in the run"};
}
void break_disconnect_with_will_reason(NodeView& view) {
    for (auto& c : view.connections) {
        for (auto& p : c.packets) {
            if (p.from_node && p.packet.type == PacketType::disconnect) p.packet.reason = 0;
        }
    }
}

Verdict one_broker_at_a_time(const NodeView& view) {
    for (std::size_t k = 1; k < view.connections.size(); ++k) {
        const auto& before = view.connections[k - 1];
        if (!before.closed || before.ended > view.connections[k].opened) {
            return "connection " + std::to_string(view.connections[k].connection) + " (broker " +
                   std::to_string(view.connections[k].relay) + ") opened while the one before was";
        }
    }
    return std::nullopt;
}
void break_one_broker_at_a_time(NodeView& view) {
    view.connections.at(0).ended = view.connections.at(1).opened + std::chrono::seconds(1);
}

}  // namespace eip2mqtt::test::conformance::checks
