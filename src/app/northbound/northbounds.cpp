#include "eip2mqtt/app/northbound/northbounds.hpp"

#include "eip2mqtt/app/history/store_and_forward_module.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"

namespace eip2mqtt::app::northbound {

Northbounds make_northbounds(const core::config::Config& config, const NorthboundParts& parts) {
    Northbounds out;
    auto tree = std::make_unique<json_tree::JsonTreeModule>(config, parts);
    auto history = history::make_store_and_forward(config, parts, *tree);
    auto node = sparkplug::make_sparkplug(config, parts, history ? &history->store() : nullptr);
    // The journal hears a sample before the tree publishes it: both ask the same connection
    // whether it is up, so every sample goes either live or to the journal.
    if (history) parts.north.add(history->store());
    // With Sparkplug as the namespace (`sparkplug.uns: false`) the tree carries the gateway's
    // own topics and its writes' answers alone.
    if (!config.sparkplug.enabled() || config.sparkplug.uns) parts.north.add(tree->tree());
    if (node) parts.north.add(node->node());
    out.tree = tree.get();
    out.node = node.get();
    out.modules.push_back(std::move(tree));
    if (history) out.modules.push_back(std::move(history));
    if (node) out.modules.push_back(std::move(node));
    return out;
}

}  // namespace eip2mqtt::app::northbound
