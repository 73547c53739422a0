#pragma once
/// The families of several MQTT connections (`mqtt` as a list): one series per connection,
/// labelled `connection`, for what the lone connection's mqtt_* and history_* families say.
///
/// Module-private to src/adapters/metrics.

#include <prometheus/metric_family.h>

#include <span>
#include <vector>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"

namespace eip2mqtt::adapters::metrics::detail {

/// Appends them to `out`; nothing when `connections` is empty.
void add_connection_families(std::vector<prometheus::MetricFamily>& out,
                             std::span<const ConnectionMetrics> connections);

}  // namespace eip2mqtt::adapters::metrics::detail
