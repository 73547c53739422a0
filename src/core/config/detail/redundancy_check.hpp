#pragma once
/// The `redundancy:` section's rules: the pair's name is a topic level of the pair's lease
/// topic, `{base_topic}/_gateway/_pair/{pair}/leader`, which fits MQTT's length.

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/diagnostic.hpp"

namespace eip2mqtt::core::config::detail {

/// Appends the problems of `config.redundancy` (nothing when there is no pair) to `out`.
void check_redundancy(const Config& config, Diagnostics& out);

}  // namespace eip2mqtt::core::config::detail
