#include "eip2mqtt/core/config/reload_plan.hpp"

#include <string_view>
#include <unordered_map>

namespace eip2mqtt::core::config {
namespace {

using Kind = KeyChange::Kind;

class Collector {
public:
    explicit Collector(ReloadPlan& plan) : plan_(plan) {}

    void add(std::string key, ReloadRule rule, Kind kind = Kind::changed) {
        plan_.needs_restart = plan_.needs_restart || rule == ReloadRule::restart;
        if (plan_.changes.size() >= ReloadPlan::max_named) {
            ++plan_.unnamed;
            return;
        }
        plan_.changes.push_back({std::move(key), rule, kind});
    }

    /// Names each key of `table` whose value differs between `a` and `b`.
    template <class Of, std::size_t N>
    void compare(std::string_view prefix, const std::array<ConfigKey<Of>, N>& table, const Of& a,
                 const Of& b) {
        for (const auto& key : table) {
            if (key.differs != nullptr && key.differs(a, b)) {
                add(std::string(prefix).append(key.name), key.rule);
            }
        }
    }

    std::size_t count() const { return plan_.changes.size() + plan_.unnamed; }

private:
    ReloadPlan& plan_;
};

void compare_connection(Collector& out, const std::string& prefix, const MqttSection& a,
                        const MqttSection& b) {
    out.compare(prefix, keys::mqtt, a, b);
    if (a.tls && b.tls) out.compare(prefix + "tls.", keys::tls, *a.tls, *b.tls);
    out.compare(prefix + "buffer.", keys::buffer, a, b);
    out.compare(prefix + "store_and_forward.", keys::store_and_forward, a.store_and_forward,
                b.store_and_forward);
}

/// The first connection's keys as `mqtt.…`, the others' as `mqtt[name].…`; another number of
/// connections restarts the gateway (each is a connection, a journal and a tree of its own).
void compare_connections(Collector& out, const Config& a, const Config& b) {
    compare_connection(out, "mqtt.", a.mqtt, b.mqtt);
    if (a.more_mqtt.size() != b.more_mqtt.size()) {
        out.add("mqtt", ReloadRule::restart);
        return;
    }
    for (std::size_t i = 0; i < a.more_mqtt.size(); ++i) {
        compare_connection(out, "mqtt[" + connection_name(b.more_mqtt[i]) + "].", a.more_mqtt[i],
                           b.more_mqtt[i]);
    }
}

void compare_sections(Collector& out, const Config& a, const Config& b) {
    out.compare("gateway.", keys::gateway, a.gateway, b.gateway);
    compare_connections(out, a, b);
    out.compare("eip.", keys::eip, a.eip, b.eip);
    out.compare("eip.commands.", keys::commands, a.eip.commands, b.eip.commands);
    out.compare("metrics.", keys::metrics, a.metrics, b.metrics);
    out.compare("sparkplug.", keys::sparkplug, a.sparkplug, b.sparkplug);
    out.compare("redundancy.", keys::redundancy, a.redundancy, b.redundancy);
}

/// The keys of a changed exchange, its tags matched by name.
void compare_exchange(Collector& out, const plan::ExchangePlan& a, const plan::ExchangePlan& b) {
    const auto before = out.count();
    const std::string prefix = "exchanges[" + b.spec.name + "].";
    out.compare(prefix, keys::exchange, a.spec, b.spec);

    std::unordered_map<std::string_view, const plan::TagSpec*> running;
    running.reserve(a.tags.size());
    for (const auto& tag : a.tags) running.emplace(tag.spec.name, &tag.spec);
    const auto tag_key = [&](const std::string& name) { return prefix + "tags[" + name + "]"; };
    for (const auto& tag : b.tags) {
        const auto found = running.find(tag.spec.name);
        if (found == running.end()) {
            out.add(tag_key(tag.spec.name), ReloadRule::live, Kind::added);
            continue;
        }
        out.compare(tag_key(tag.spec.name) + ".", keys::tag, *found->second, tag.spec);
        running.erase(found);
    }
    for (const auto& tag : a.tags) {
        if (running.contains(tag.spec.name)) {
            out.add(tag_key(tag.spec.name), ReloadRule::live, Kind::removed);
        }
    }
    // The same tags in another order: the exchange's byte map reads the same, but its tag
    // indices (and so the plan) changed. Plans that differ only by what the sections resolve
    // (gateway.timestamp, say) were named with the sections.
    if (out.count() == before && a.tags != b.tags) out.add(prefix + "tags", ReloadRule::live);
}

}  // namespace

std::string ReloadPlan::describe(ReloadRule rule) const {
    std::string text;
    for (const auto& change : changes) {
        if (change.rule != rule) continue;
        if (!text.empty()) text += ", ";
        text += change.key;
        if (change.kind == Kind::added) text += " (added)";
        if (change.kind == Kind::removed) text += " (removed)";
    }
    if (rule == ReloadRule::live && unnamed > 0) {
        text +=
            (text.empty() ? "" : ", ") + std::string("and ") + std::to_string(unnamed) + " more";
    }
    return text;
}

ReloadPlan plan_reload(const Config& running,
                       std::span<const plan::ExchangePlan* const> running_exchanges,
                       const Config& next, std::span<const plan::ExchangePlan> next_exchanges) {
    ReloadPlan plan;
    Collector out(plan);
    compare_sections(out, running, next);

    std::unordered_map<std::string_view, const plan::ExchangePlan*> by_name;
    by_name.reserve(running_exchanges.size());
    for (const auto* exchange : running_exchanges) by_name.emplace(exchange->spec.name, exchange);
    for (const auto& exchange : next_exchanges) {
        const auto found = by_name.find(exchange.spec.name);
        if (found == by_name.end()) {
            out.add("exchanges[" + exchange.spec.name + "]", ReloadRule::live, Kind::added);
            continue;
        }
        if (!(*found->second == exchange)) compare_exchange(out, *found->second, exchange);
        by_name.erase(found);
    }
    for (const auto* exchange : running_exchanges) {
        if (by_name.contains(exchange->spec.name)) {
            out.add("exchanges[" + exchange->spec.name + "]", ReloadRule::live, Kind::removed);
        }
    }
    return plan;
}

}  // namespace eip2mqtt::core::config
