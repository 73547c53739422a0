#include "eip2mqtt/core/config/config.hpp"

#include <algorithm>
#include <string_view>
#include <utility>

#include "core/config/detail/validator.hpp"

namespace eip2mqtt::core::config {
namespace {

auto find_key(const std::vector<std::pair<std::string, Mark>>& keys, std::string_view key) {
    return std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.first == key; });
}

}  // namespace

const Mark& Marks::of(std::string_view key) const {
    const auto it = find_key(keys, key);
    return it == keys.end() ? node : it->second;
}

std::size_t sparkplug_connection(const Config& config) {
    if (config.sparkplug.connection.empty()) return 0;
    const auto connections = mqtt_connections(config);
    for (std::size_t i = 0; i < connections.size(); ++i) {
        if (connection_name(*connections[i]) == config.sparkplug.connection) return i;
    }
    return 0;
}

bool Marks::contains(std::string_view key) const { return find_key(keys, key) != keys.end(); }

bool Marks::add(std::string_view key, const Mark& at) {
    if (contains(key)) return false;
    keys.emplace_back(key, at);
    return true;
}

Diagnostics validate(const Config& config) { return detail::Validator(config).run(); }

std::vector<plan::ExchangePlan> make_plans(const Config& config) {
    std::string problem;  // none: the configuration passed validate()
    const auto topic_template = plan::TopicTemplate::parse(config.mqtt.topic_template, problem);
    const plan::TopicLayout layout{topic_template ? &*topic_template : nullptr,
                                   &config.gateway.location};
    std::vector<plan::ExchangePlan> plans;
    plans.reserve(config.exchanges.size());
    for (const auto& exchange : config.exchanges) {
        plan::ExchangeSpec spec = exchange.spec;
        spec.tags.clear();
        spec.tags.reserve(exchange.tags.size());
        for (const auto& tag : exchange.tags) spec.tags.push_back(tag.spec);
        plans.push_back(plan::make_exchange_plan(std::move(spec), config.mqtt.base_topic,
                                                 config.gateway.exchange_defaults, layout));
    }
    return plans;
}

}  // namespace eip2mqtt::core::config
