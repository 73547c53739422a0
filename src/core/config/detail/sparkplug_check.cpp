#include "core/config/detail/sparkplug_check.hpp"

#include <string>
#include <string_view>

#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::config::detail {
namespace {

/// Sparkplug B 3.0 topic elements: non-empty UTF-8 without '+', '/' or '#'. Control characters
/// are refused too, as in every topic of ours.
std::string id_problem(std::string_view id) {
    if (id.empty()) return "is empty";
    if (id.find_first_of("/+#") != std::string_view::npos) {
        return "contains '/', '+' or '#' (Sparkplug topic elements may not)";
    }
    return std::string(plan::text_problem(id));
}

}  // namespace

void check_sparkplug(const Config& config, Diagnostics& out) {
    const auto& sparkplug = config.sparkplug;
    if (!sparkplug.enabled()) return;
    const auto check = [&](std::string_view what, const std::string& id, const Mark& at) {
        if (const auto problem = id_problem(id); !problem.empty()) {
            out.push_back({at, std::string(what) + " " + in_quotes(id) + " " + problem});
        }
    };
    check("sparkplug group_id", sparkplug.group_id, sparkplug.marks.of("group_id"));
    if (sparkplug.marks.contains("edge_node_id")) {
        check("sparkplug edge_node_id", sparkplug.edge_node_id, sparkplug.marks.of("edge_node_id"));
    } else {
        check("gateway id (the Sparkplug edge_node_id)", config.gateway.id,
              config.gateway.marks.of("id"));
    }
    if (sparkplug.marks.contains("primary_host_id")) {
        check("sparkplug primary_host_id", sparkplug.primary_host_id,
              sparkplug.marks.of("primary_host_id"));
    }
    if (config.mqtt.store_and_forward.enabled && !sparkplug.uns) {
        out.push_back({sparkplug.marks.of("uns"),
                       "mqtt.store_and_forward replays history on the JSON tree's _history "
                       "topics: it needs sparkplug uns: true"});
    }
    for (const auto& exchange : config.exchanges) {
        // An empty name is reported by the exchange checks already.
        if (exchange.spec.name.empty()) continue;
        check("exchange name (a Sparkplug device ID)", exchange.spec.name,
              exchange.marks.of("name"));
    }
}

}  // namespace eip2mqtt::core::config::detail
