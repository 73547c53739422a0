#pragma once
/// The `sparkplug:` section's rules (issue #15): its IDs, and every exchange's name, which is a
/// device ID, are Sparkplug topic elements, and the topics they make fit MQTT's length.

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/diagnostic.hpp"

namespace eip2mqtt::core::config::detail {

/// Appends the problems of `config.sparkplug` (nothing when Sparkplug is off) to `out`.
void check_sparkplug(const Config& config, Diagnostics& out);

}  // namespace eip2mqtt::core::config::detail
