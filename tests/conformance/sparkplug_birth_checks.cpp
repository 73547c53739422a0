// The checks of births against DATA: a device's DATA after its DBIRTH, every device born again
// right after each NBIRTH and before any DATA, DATA stopped at a rebirth request until the
// births, and a device that stops being reachable declared dead, then born again.

#include <set>

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

/// The devices alive (a DBIRTH and no DDEATH since) before packet `end` of `c`, since its
/// last NBIRTH before `end`.
std::set<std::string> alive_before(const NodeView& view, const NodeConnection& c, std::size_t end) {
    std::set<std::string> alive;
    for (std::size_t i = 0; i < end; ++i) {
        if (!c.packets[i].from_node) continue;
        const auto t = type_of(view, c.packets[i]);
        const auto device = device_of(view, c.packets[i].packet.topic);
        if (t == "NBIRTH") alive.clear();
        if (t == "DBIRTH") alive.insert(device);
        if (t == "DDEATH") alive.erase(device);
    }
    return alive;
}

}  // namespace

Verdict device_data_after_its_birth(const NodeView& view) {
    return each_sent(view, "DDATA", [&](const NodeConnection& c, std::size_t i) -> Verdict {
        if (alive_before(view, c, i).contains(device_of(view, c.packets[i].packet.topic))) {
            return std::nullopt;
        }
        return where(c, i) + ": its device has no DBIRTH since the NBIRTH (or died since)";
    });
}
void break_device_data_after_its_birth(NodeView& view) {
    for (auto& c : view.connections) {
        std::erase_if(c.packets, [&](const NodePacket& p) {
            return p.from_node && type_of(view, p) == "DBIRTH";
        });
    }
}

Verdict births_complete_before_data(const NodeView& view) {
    for (const auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            if (!c.packets[i].from_node || type_of(view, c.packets[i]) != "NBIRTH") continue;
            // Born before this NBIRTH: born again by the DBIRTHs right after it.
            auto owed = alive_before(view, c, i);
            for (auto k = i + 1; k < c.packets.size() && !owed.empty(); ++k) {
                const auto t = type_of(view, c.packets[k]);
                if (!c.packets[k].from_node || t.empty()) continue;
                if (t != "DBIRTH") {
                    return where(c, k) + ": before the DBIRTH of " + *owed.begin() +
                           ", born before the NBIRTH";
                }
                owed.erase(device_of(view, c.packets[k].packet.topic));
            }
        }
    }
    return std::nullopt;
}
void break_births_complete_before_data(NodeView& view) {
    for (auto& c : view.connections) {
        bool born = false;
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto t = type_of(view, c.packets[i]);
            if (!c.packets[i].from_node) continue;
            if (t == "DBIRTH") born = true;
            if (t == "NBIRTH" && born && i + 1 < c.packets.size()) {
                // A DATA between a rebirth's NBIRTH and its DBIRTHs.
                auto data = c.packets[i];
                data.packet.topic = view.topic("NDATA");
                c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(i + 1), data);
                return;
            }
        }
    }
}

Verdict rebirth_request_stops_data(const NodeView& view) {
    bool any = false;
    for (const auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            if (!is_rebirth_request(view, c.packets[i])) continue;
            any = true;
            bool reborn = false;
            for (auto k = i + 1; k < c.packets.size() && !reborn; ++k) {
                const auto t = type_of(view, c.packets[k]);
                if (!c.packets[k].from_node) continue;
                if (t == "NBIRTH") reborn = true;
                if (is_data(t) && c.packets[k].at - c.packets[i].at > in_flight) {
                    return where(c, k) + ": DATA after a rebirth request, before its NBIRTH";
                }
            }
            if (!reborn && !c.closed) return where(c, i) + ": no NBIRTH after this request";
        }
    }
    return any ? Verdict{} : Verdict{"no rebirth request reached the node in the run"};
}
void break_rebirth_request_stops_data(NodeView& view) {
    for (auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            if (!is_rebirth_request(view, c.packets[i])) continue;
            auto late = c.packets[i];
            late.from_node = true;
            late.packet.topic = view.topic("NDATA");
            late.at += in_flight * 2;
            c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(i + 1), late);
            return;
        }
    }
}

Verdict silent_device_dies_and_returns(const NodeView& view) {
    const auto silent = view.marks.find("line silent");
    const auto back = view.marks.find("line back");
    if (silent == view.marks.end() || back == view.marks.end()) return "the run has no outage";
    bool died = false, reborn = false;
    for (const auto& c : view.connections) {
        for (const auto& p : c.packets) {
            if (!p.from_node || device_of(view, p.packet.topic) != "line") continue;
            const auto t = type_of(view, p);
            if (t == "DDEATH" && p.at > silent->second && p.at < back->second) died = true;
            if (t == "DBIRTH" && died && p.at > back->second) reborn = true;
        }
    }
    if (!died) return "no DDEATH of line while the plant was silent";
    if (!reborn) return "no DBIRTH of line once the plant was back";
    return std::nullopt;
}
void break_silent_device_dies(NodeView& view) {
    for (auto& c : view.connections) {
        std::erase_if(c.packets, [&](const NodePacket& p) {
            return p.from_node && type_of(view, p) == "DDEATH";
        });
    }
}

}  // namespace eip2mqtt::test::conformance::checks
