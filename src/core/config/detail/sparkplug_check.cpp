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

/// "makes topic '{pattern}' N bytes long (MQTT allows 65535)", when it does.
std::string topic_length_problem(std::string_view pattern, std::size_t bytes) {
    if (bytes <= plan::max_topic_bytes) return {};
    return "makes topic '" + std::string(pattern) + "' " + std::to_string(bytes) +
           " bytes long (MQTT allows " + std::to_string(plan::max_topic_bytes) + ")";
}

/// Every Sparkplug topic fits MQTT's length: the longest of the node's is
/// spBv1.0/{group}/NBIRTH/{node}, of a device's spBv1.0/{group}/DBIRTH/{node}/{device}. A group
/// and node too long for the node's topics are said once, and no device is checked then.
void check_topic_lengths(const Config& config, Diagnostics& out) {
    const auto& sparkplug = config.sparkplug;
    const auto& node_id = sparkplug_node_id(config);
    constexpr std::string_view root = "spBv1.0/";
    constexpr std::string_view birth = "/NBIRTH/";
    const std::size_t node_bytes =
        root.size() + sparkplug.group_id.size() + birth.size() + node_id.size();
    const auto node_problem =
        topic_length_problem("spBv1.0/{group_id}/NBIRTH/{edge_node_id}", node_bytes);
    if (!node_problem.empty()) {
        out.push_back({sparkplug.marks.of("group_id"),
                       "sparkplug group_id " + in_quotes(sparkplug.group_id) + " " + node_problem});
        return;
    }
    if (!sparkplug.primary_host_id.empty()) {
        constexpr std::string_view state = "spBv1.0/STATE/";
        const auto problem = topic_length_problem("spBv1.0/STATE/{primary_host_id}",
                                                  state.size() + sparkplug.primary_host_id.size());
        if (!problem.empty()) {
            out.push_back({sparkplug.marks.of("primary_host_id"),
                           "sparkplug primary_host_id " + in_quotes(sparkplug.primary_host_id) +
                               " " + problem});
        }
    }
    for (const auto& exchange : config.exchanges) {
        const auto problem =
            topic_length_problem("spBv1.0/{group_id}/DBIRTH/{edge_node_id}/{exchange}",
                                 node_bytes + 1 + exchange.spec.name.size());
        if (!problem.empty()) {
            out.push_back({exchange.marks.of("name"), "exchange name (a Sparkplug device ID) " +
                                                          in_quotes(exchange.spec.name) + " " +
                                                          problem});
        }
    }
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
    } else if (!config.redundancy.enabled()) {
        check("gateway id (the Sparkplug edge_node_id)", config.gateway.id,
              config.gateway.marks.of("id"));
    }  // else the pair's name, which check_redundancy holds to the same rules
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
    check_topic_lengths(config, out);
}

}  // namespace eip2mqtt::core::config::detail
