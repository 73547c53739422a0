// The checks that follow the node through its sessions: DATA announced by the birth before it
// and changed since the last report, the births of a session complete before DATA, device
// deaths when the plant goes silent, what a rebirth request stops, and the NDEATH's payload.

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

/// The value fields of a metric, to compare two reports of it.
std::string value_bytes(const SparkplugPayload::Metric& m) {
    SparkplugPayload::Metric only;
    only.set_is_null(m.is_null());
    switch (m.value_case()) {
        case SparkplugPayload::Metric::kIntValue:
            only.set_int_value(m.int_value());
            break;
        case SparkplugPayload::Metric::kLongValue:
            only.set_long_value(m.long_value());
            break;
        case SparkplugPayload::Metric::kFloatValue:
            only.set_float_value(m.float_value());
            break;
        case SparkplugPayload::Metric::kDoubleValue:
            only.set_double_value(m.double_value());
            break;
        case SparkplugPayload::Metric::kBooleanValue:
            only.set_boolean_value(m.boolean_value());
            break;
        case SparkplugPayload::Metric::kStringValue:
            only.set_string_value(m.string_value());
            break;
        default:
            break;
    }
    return only.SerializeAsString();
}

/// Per birth topic's scope (the node, or a device): the aliases its last birth announced and
/// the value last reported for each.
struct Reported {
    std::set<std::uint64_t> announced;
    std::map<std::uint64_t, std::string> last;
};

/// Walks each connection's births and DATA: `f` is told each DATA metric with what its scope
/// announced and reported before it; a birth starts its scope afresh.
Verdict each_data_metric(
    const NodeView& view,
    const std::function<Verdict(const SparkplugPayload::Metric&, const Reported&)>& f) {
    for (const auto& c : view.connections) {
        std::map<std::string, Reported> scopes;  // "" the node, else the device
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto& p = c.packets[i];
            const auto t = type_of(view, p);
            if (!p.from_node || !p.payload || (t != "NBIRTH" && t != "DBIRTH" && !is_data(t))) {
                continue;
            }
            const auto scope = device_of(view, p.packet.topic);
            auto& reported = scopes[scope];
            if (t == "NBIRTH" || t == "DBIRTH") reported = {};
            for (const auto& m : p.payload->metrics()) {
                if (is_data(t) && !m.is_historical()) {
                    if (auto v = f(m, reported)) {
                        return where(c, i) + ": alias " + std::to_string(m.alias()) + " " + *v;
                    }
                }
                if (t == "NBIRTH" || t == "DBIRTH") reported.announced.insert(m.alias());
                reported.last[m.alias()] = value_bytes(m);
            }
        }
    }
    return std::nullopt;
}

}  // namespace

Verdict data_announced_by_birth(const NodeView& view) {
    return each_data_metric(view, [](auto& m, const Reported& r) -> Verdict {
        if (!r.announced.contains(m.alias())) return "was not in the birth before it";
        return std::nullopt;
    });
}
void break_data_announced(NodeView& view) {
    auto& payload = *first_sent(view, "DDATA").payload;
    payload.mutable_metrics(0)->set_alias(0xFFFFFFFFFFull);
}

Verdict data_carries_changes(const NodeView& view) {
    return each_data_metric(view, [](auto& m, const Reported& r) -> Verdict {
        const auto last = r.last.find(m.alias());
        if (last != r.last.end() && last->second == value_bytes(m)) return "did not change";
        return std::nullopt;
    });
}
void break_data_carries_changes(NodeView& view) {
    auto& payload = *first_sent(view, "DDATA").payload;
    auto repeat = payload.metrics(0);
    *payload.add_metrics() = repeat;  // the same value again, in the same payload
}

Verdict data_in_time_order(const NodeView& view) {
    return each_sent(view, "", [&](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto& payload = c.packets[i].payload;
        if (!payload) return std::nullopt;
        std::map<std::string, std::uint64_t> latest;
        for (const auto& m : payload->metrics()) {
            if (m.is_historical()) continue;
            const auto key = m.has_alias() ? std::to_string(m.alias()) : m.name();
            const auto [it, first] = latest.emplace(key, m.timestamp());
            if (!first && m.timestamp() < it->second) return where(c, i) + ": out of time order";
            it->second = m.timestamp();
        }
        return std::nullopt;
    });
}
void break_data_in_time_order(NodeView& view) {
    auto& payload = *first_sent(view, "DDATA").payload;
    auto earlier = payload.metrics(0);
    earlier.set_timestamp(earlier.timestamp() - 1000);
    *payload.add_metrics() = earlier;
}

Verdict ndeath_is_bd_seq_alone(const NodeView& view) {
    return each_sent(view, "NDEATH", [](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto& payload = c.packets[i].payload;
        if (!payload || payload->metrics_size() != 1 || payload->metrics(0).name() != "bdSeq") {
            return where(c, i) + ": not the bdSeq metric alone";
        }
        SparkplugPayload will;
        if (!c.connect.will || !will.ParseFromString(c.connect.will->payload) ||
            will.metrics_size() != 1 ||
            will.metrics(0).long_value() != payload->metrics(0).long_value()) {
            return where(c, i) + ": another bdSeq than the connection's will";
        }
        return std::nullopt;
    });
}
void break_ndeath_is_bd_seq_alone(NodeView& view) {
    first_sent(view, "NDEATH").payload->add_metrics()->set_name("extra");
}
void break_ndeath_bd_seq(NodeView& view) {
    auto& m = *first_sent(view, "NDEATH").payload->mutable_metrics(0);
    m.set_long_value(m.long_value() + 1);
}

Verdict metric_names_apart_in_case(const NodeView& view) {
    return each_sent(view, "", [&](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto t = type_of(view, c.packets[i]);
        if ((t != "NBIRTH" && t != "DBIRTH") || !c.packets[i].payload) return std::nullopt;
        std::set<std::string> lower;
        for (const auto& m : c.packets[i].payload->metrics()) {
            auto name = m.name();
            std::transform(name.begin(), name.end(), name.begin(),
                           [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
            if (!lower.insert(name).second) return where(c, i) + ": " + m.name() + " twice in case";
        }
        return std::nullopt;
    });
}
void break_metric_names_apart_in_case(NodeView& view) {
    auto& payload = *first_sent(view, "DBIRTH").payload;
    auto twin = payload.metrics(0);
    twin.set_name(twin.name() + "x");
    auto upper = twin;
    std::transform(upper.mutable_name()->begin(), upper.mutable_name()->end(),
                   upper.mutable_name()->begin(),
                   [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    *payload.add_metrics() = twin;
    *payload.add_metrics() = upper;
}

Verdict ids_are_topic_elements(const NodeView& view) {
    const auto bad = [](const std::string& id) {
        return id.empty() || id.find_first_of("+#/") != std::string::npos;
    };
    if (bad(view.group) || bad(view.node)) return "the group or edge node id";
    return each_sent(view, "", [&](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto t = type_of(view, c.packets[i]);
        if (t.front() != 'D') return std::nullopt;
        if (bad(device_of(view, c.packets[i].packet.topic))) return where(c, i) + ": device id";
        return std::nullopt;
    });
}
void break_ids_are_topic_elements(NodeView& view) {
    first_sent(view, "DBIRTH").packet.topic += "+";
}

Verdict aliases_unique_in_the_node(const NodeView& view) {
    for (const auto& c : view.connections) {
        std::map<std::uint64_t, std::string> owner;  // alias -> scope, since the last NBIRTH
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto t = type_of(view, c.packets[i]);
            if (!c.packets[i].from_node || (t != "NBIRTH" && t != "DBIRTH")) continue;
            if (t == "NBIRTH") owner.clear();
            const auto scope = device_of(view, c.packets[i].packet.topic);
            for (const auto& m : c.packets[i].payload->metrics()) {
                if (!m.has_alias()) continue;
                const auto [it, added] = owner.emplace(m.alias(), scope + "/" + m.name());
                if (!added && it->second != scope + "/" + m.name()) {
                    return where(c, i) + ": alias " + std::to_string(m.alias()) + " of " +
                           m.name() + " is " + it->second + "'s";
                }
            }
        }
    }
    return std::nullopt;
}
void break_aliases_unique(NodeView& view) {
    auto& payload = *first_sent(view, "DBIRTH").payload;
    payload.mutable_metrics(1)->set_alias(payload.metrics(0).alias());
}

Verdict device_ids_unique(const NodeView& view) {
    for (const auto& c : view.connections) {
        std::set<std::string> born;  // since the last NBIRTH, and alive
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            const auto t = type_of(view, c.packets[i]);
            const auto device = device_of(view, c.packets[i].packet.topic);
            if (!c.packets[i].from_node) continue;
            if (t == "NBIRTH") born.clear();
            if (t == "DDEATH") born.erase(device);
            if (t == "DBIRTH" && !born.insert(device).second) {
                return where(c, i) + ": a second live device " + device;
            }
        }
    }
    return std::nullopt;
}
void break_device_ids_unique(NodeView& view) {
    for (auto& c : view.connections) {
        for (std::size_t i = 0; i < c.packets.size(); ++i) {
            if (!c.packets[i].from_node || type_of(view, c.packets[i]) != "DBIRTH") continue;
            auto twin = c.packets[i];
            c.packets.insert(c.packets.begin() + static_cast<std::ptrdiff_t>(i + 1), twin);
            return;
        }
    }
}

}  // namespace eip2mqtt::test::conformance::checks
