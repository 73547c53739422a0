// The checks of what the primary host's STATE and a host's rebirth request make the node do:
// births only after a valid online STATE; a valid offline one ends its session with the broker
// (NDEATH, DISCONNECT, the next broker), an older one nothing; DATA stops at a rebirth request,
// and every birth follows.

#include <algorithm>

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

constexpr std::string_view primary_host = "scada";

/// The STATE that let the births of `c` start: the last one handed to the node before its
/// first NBIRTH; with the largest timestamp handed before it. nullopt: no birth, or none.
struct Enabling {
    std::size_t birth = 0;
    std::optional<State> state;
    std::int64_t newest_before = -1;
};
std::optional<Enabling> enabling_state(const NodeView& view, const NodeConnection& c) {
    Enabling e;
    for (std::size_t i = 0; i < c.packets.size(); ++i) {
        if (c.packets[i].from_node && type_of(view, c.packets[i]) == "NBIRTH") {
            e.birth = i;
            return e;
        }
        if (const auto state = state_of(c.packets[i])) {
            if (e.state) e.newest_before = std::max(e.newest_before, e.state->timestamp);
            e.state = state;
        }
    }
    return std::nullopt;
}

/// A STATE of the primary host handed to a born node, offline, and valid (its timestamp not
/// older than the last online one): what the node sent after it on that connection.
struct Offline {
    std::size_t at = 0;
    bool valid = false;
};
std::vector<Offline> offline_states(const NodeView& view, const NodeConnection& c) {
    std::vector<Offline> out;
    bool born = false;
    std::int64_t last_online = -1;
    for (std::size_t i = 0; i < c.packets.size(); ++i) {
        if (c.packets[i].from_node && type_of(view, c.packets[i]) == "NBIRTH") born = true;
        const auto state = state_of(c.packets[i]);
        if (!state || state->host != primary_host) continue;
        if (state->online) {
            last_online = std::max(last_online, state->timestamp);
        } else if (born) {
            out.push_back({i, state->timestamp >= last_online});
        }
    }
    return out;
}

}  // namespace

Verdict births_wait_for_the_host(const NodeView& view, const HostRule& rule) {
    for (const auto& c : view.connections) {
        const auto e = enabling_state(view, c);
        if (!e) continue;
        if (!e->state) return where(c, e->birth) + ": no STATE before the births";
        if (rule == HostRule::id && e->state->host != primary_host) {
            return where(c, e->birth) + ": after a STATE of " + e->state->host;
        }
        if (rule == HostRule::online && !e->state->online) {
            return where(c, e->birth) + ": after an offline STATE";
        }
        if (rule == HostRule::timestamp && e->state->timestamp < e->newest_before) {
            return where(c, e->birth) + ": after a STATE older than one before it";
        }
    }
    return std::nullopt;
}

void break_births_wait_for_the_host(NodeView& view, const HostRule& rule) {
    for (auto& c : view.connections) {
        const auto e = enabling_state(view, c);
        if (!e || !e->state) continue;
        if (rule == HostRule::present) {
            // No STATE at all before the births.
            c.packets.erase(
                std::remove_if(c.packets.begin(),
                               c.packets.begin() + static_cast<std::ptrdiff_t>(e->birth),
                               [](const NodePacket& p) { return state_of(p).has_value(); }),
                c.packets.begin() + static_cast<std::ptrdiff_t>(e->birth));
            return;
        }
        // The enabling STATE is the last one before the births.
        for (auto i = e->birth; i-- > 0;) {
            auto& packet = c.packets[i].packet;
            if (!state_of(c.packets[i])) continue;
            if (rule == HostRule::id) {
                packet.topic = "spBv1.0/STATE/another";
            } else if (rule == HostRule::online) {
                packet.payload = R"({"online":false,"timestamp":)" +
                                 std::to_string(state_of(c.packets[i])->timestamp) + "}";
            } else {
                // Older than one before it: the connection needs two STATEs.
                if (e->newest_before < 0) break;
                packet.payload = R"({"online":true,"timestamp":0})";
            }
            return;
        }
    }
}

Verdict offline_ends_the_session(const NodeView& view) {
    bool any = false;
    for (const auto& c : view.connections) {
        for (const auto& offline : offline_states(view, c)) {
            if (!offline.valid) continue;
            any = true;
            bool disconnected = false;
            bool death = false;
            const auto read_at = c.packets[offline.at].at;
            for (auto i = offline.at + 1; i < c.packets.size(); ++i) {
                const auto& p = c.packets[i];
                if (!p.from_node) continue;
                const auto t = type_of(view, p);
                if (p.packet.type == PacketType::disconnect) disconnected = true;
                if (t == "NDEATH" && !disconnected) death = true;
                if (t.empty() || t == "NDEATH") continue;
                if (disconnected || p.at - read_at > in_flight) {
                    return where(c, i) + ": after the host's offline STATE";
                }
            }
            // Its DISCONNECT ends the session: who closes the socket first is a race.
            if (!death || !disconnected) {
                return where(c, offline.at) + ": no NDEATH, DISCONNECT and close after it";
            }
        }
    }
    return any ? Verdict{} : Verdict{"no valid offline STATE reached a born node in the run"};
}
void break_offline_ends_the_session(NodeView& view) {
    for (auto& c : view.connections) {
        for (const auto& offline : offline_states(view, c)) {
            if (!offline.valid) continue;
            // DATA long after it, on a connection the node never left.
            auto late = c.packets[offline.at];
            late.from_node = true;
            late.packet.topic = view.topic("NDATA");
            late.at += in_flight * 2;
            c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(offline.at + 1),
                             std::move(late));
            return;
        }
    }
}

Verdict older_offline_keeps_the_session(const NodeView& view) {
    bool any = false;
    for (const auto& c : view.connections) {
        for (const auto& offline : offline_states(view, c)) {
            if (offline.valid) continue;
            any = true;
            // DATA goes on after it on this connection, before any NDEATH.
            for (auto i = offline.at + 1; i < c.packets.size(); ++i) {
                const auto t = type_of(view, c.packets[i]);
                if (!c.packets[i].from_node) continue;
                if (is_data(t)) break;
                if (t == "NDEATH" || c.packets[i].packet.type == PacketType::disconnect) {
                    return where(c, i) + ": after an offline STATE older than the online one";
                }
            }
        }
    }
    return any ? Verdict{} : Verdict{"no older offline STATE reached a born node in the run"};
}
void break_older_offline_keeps_the_session(NodeView& view) {
    for (auto& c : view.connections) {
        for (const auto& offline : offline_states(view, c)) {
            if (offline.valid) continue;
            auto death = c.packets[offline.at];
            death.from_node = true;
            death.packet.topic = view.topic("NDEATH");
            c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(offline.at + 1),
                             std::move(death));
            return;
        }
    }
}

Verdict offline_walks_to_the_next_broker(const NodeView& view) {
    bool any = false;
    for (std::size_t k = 0; k + 1 < view.connections.size(); ++k) {
        const auto& c = view.connections[k];
        const auto offline = offline_states(view, c);
        if (std::none_of(offline.begin(), offline.end(), [](auto& o) { return o.valid; })) {
            continue;
        }
        any = true;
        const auto& next = view.connections[k + 1];
        if (next.relay != (c.relay + 1) % 2) {
            return "connection " + std::to_string(next.connection) + ": broker " +
                   std::to_string(next.relay) + " after leaving broker " + std::to_string(c.relay);
        }
    }
    return any ? Verdict{} : Verdict{"the node never left a broker for its host in the run"};
}
void break_offline_walks(NodeView& view) {
    for (std::size_t k = 0; k + 1 < view.connections.size(); ++k) {
        view.connections[k + 1].relay = view.connections[k].relay;
    }
}

}  // namespace eip2mqtt::test::conformance::checks
