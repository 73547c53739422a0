#include "core/config/detail/connection_list_check.hpp"

#include <algorithm>
#include <string>

namespace eip2mqtt::core::config::detail {
namespace {

bool name_characters_ok(const std::string& name) {
    return std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    });
}

/// `inner` lies under `outer` (and is not it): a topic of one could be read as of the other.
bool nested(const std::string& inner, const std::string& outer) {
    return inner.size() > outer.size() && inner.starts_with(outer) && inner[outer.size()] == '/';
}

void check_names(const std::vector<const MqttSection*>& connections, Diagnostics& out) {
    for (std::size_t i = 0; i < connections.size(); ++i) {
        const auto& mqtt = *connections[i];
        const std::string entry = "mqtt connection " + std::to_string(i + 1) + " ";
        if (mqtt.name.empty()) {
            if (connections.size() > 1) {
                out.push_back({mqtt.marks.node,
                               entry + "has no 'name': each connection of a list names itself "
                                       "(in logs, metrics and its journal's file)"});
            }
            continue;
        }
        if (!name_characters_ok(mqtt.name)) {
            out.push_back({mqtt.marks.of("name"),
                           "mqtt name " + in_quotes(mqtt.name) +
                               " may hold only letters, digits, '_' and '-' (it names a file)"});
            continue;
        }
        const auto first = std::find_if(connections.begin(), connections.end(),
                                        [&](const auto* c) { return c->name == mqtt.name; });
        if (first != connections.begin() + static_cast<std::ptrdiff_t>(i)) {
            out.push_back({mqtt.marks.of("name"),
                           "mqtt name " + in_quotes(mqtt.name) + " names two connections"});
        }
    }
}

}  // namespace

void check_connection_list(const Config& config, Diagnostics& out) {
    const auto connections = mqtt_connections(config);
    check_names(connections, out);
    for (const auto& more : config.more_mqtt) {
        if (nested(more.base_topic, config.mqtt.base_topic) ||
            nested(config.mqtt.base_topic, more.base_topic)) {
            out.push_back({more.marks.of("base_topic"),
                           "base_topic " + in_quotes(more.base_topic) +
                               " and the first "
                               "connection's " +
                               in_quotes(config.mqtt.base_topic) +
                               " lie one under the other: give the same one, or two apart"});
        }
        if (more.marks.contains("topic_template")) {
            out.push_back({more.marks.of("topic_template"),
                           "topic_template is the first connection's: every connection lays "
                           "the tags out alike, each under its own base_topic"});
        }
    }
    const auto& wanted = config.sparkplug.connection;
    if (wanted.empty()) return;
    const bool known = std::any_of(connections.begin(), connections.end(),
                                   [&](const auto* c) { return connection_name(*c) == wanted; });
    if (!known) {
        out.push_back({config.sparkplug.marks.of("connection"),
                       "sparkplug connection " + in_quotes(wanted) +
                           " is not the name of an mqtt connection"});
    }
}

}  // namespace eip2mqtt::core::config::detail
