#pragma once
/// A gateway-wide counter table (core/counter_table.hpp) as the metrics topic writes it.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "eip2mqtt/core/counter_table.hpp"

namespace eip2mqtt::app::northbound::json_tree {

/// The fields of `counters` in the metrics topic, added to `into`: a number, or an object by key.
template <class Fields, class Counters>
void add_counter_set(nlohmann::json& into, const Fields& fields, const Counters& counters) {
    for (const auto& field : fields) {
        if (!field.in(core::in_metrics_topic)) continue;
        auto& value = into[std::string(field.name)];
        core::for_each_count(field, counters, [&](std::string_view key, std::uint64_t count) {
            if (key.empty()) {
                value = count;
            } else {
                value[std::string(key)] = count;
            }
        });
    }
}

}  // namespace eip2mqtt::app::northbound::json_tree
