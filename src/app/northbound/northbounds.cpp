#include "eip2mqtt/app/northbound/northbounds.hpp"

#include "eip2mqtt/app/history/store_and_forward_module.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"

namespace eip2mqtt::app::northbound {
namespace {

/// One MQTT connection's tree and journal.
struct Connection {
    std::unique_ptr<json_tree::JsonTreeModule> tree;
    std::unique_ptr<history::StoreAndForwardModule> history;
};

/// A tree that connects again says the retained state to itself alone: the other
/// connections' trees keep out of it, and the Sparkplug node too unless the tree is the first
/// connection's (whose reconnect always reached it).
void scope_republishes(const Northbounds& out, Northbound* node, FanOut& fan_out) {
    if (out.trees.size() < 2) return;
    for (std::size_t i = 0; i < out.trees.size(); ++i) {
        std::vector<Northbound*> skipped;
        for (std::size_t j = 0; j < out.trees.size(); ++j) {
            if (j != i) skipped.push_back(&out.trees[j]->tree());
        }
        if (i > 0 && node != nullptr) skipped.push_back(node);
        out.trees[i]->set_republish_scope(
            [&fan_out, skipped = std::move(skipped)](const std::function<void()>& run) {
                fan_out.excluding(skipped, run);
            });
    }
}

}  // namespace

Northbounds make_northbounds(const core::config::Config& config, const NorthboundParts& parts) {
    Northbounds out;
    std::vector<Connection> connections;
    for (std::size_t i = 0; i <= config.more_mqtt.size(); ++i) {
        auto tree = std::make_unique<json_tree::JsonTreeModule>(config, parts, i);
        auto history = history::make_store_and_forward(config, parts, *tree);
        connections.push_back({std::move(tree), std::move(history)});
    }
    auto& carrier = connections[core::config::sparkplug_connection(config)];
    auto node = sparkplug::make_sparkplug(config, parts,
                                          carrier.history ? &carrier.history->store() : nullptr);
    // The journal hears a sample before the tree publishes it: both ask the same connection
    // whether it is up, so every sample goes either live or to the journal.
    // With Sparkplug as the namespace (`sparkplug.uns: false`) the trees carry the gateway's
    // own topics and their writes' answers alone.
    const bool trees_hear = !config.sparkplug.enabled() || config.sparkplug.uns;
    for (auto& connection : connections) {
        if (connection.history) parts.north.add(connection.history->store());
        if (trees_hear) parts.north.add(connection.tree->tree());
        out.trees.push_back(connection.tree.get());
    }
    if (node) parts.north.add(node->node());
    out.tree = out.trees.front();
    out.node = node.get();
    if (trees_hear) scope_republishes(out, node ? &node->node() : nullptr, parts.north);
    for (auto& connection : connections) {
        out.modules.push_back(std::move(connection.tree));
        if (connection.history) out.modules.push_back(std::move(connection.history));
    }
    if (node) out.modules.push_back(std::move(node));
    return out;
}

}  // namespace eip2mqtt::app::northbound
