#pragma once
/// The role's counters in the metrics topic: a pair's `pair` object (docs/schema/metrics.json,
/// the table of pair_counters.hpp); a single unit has none.

#include <nlohmann/json_fwd.hpp>

namespace eip2mqtt::app {
struct MetricsSources;
}

namespace eip2mqtt::app::redundancy {

/// Adds the `pair` object to `metrics` when `sources` has a pair's counters.
void add_role_metrics(nlohmann::json& metrics, const MetricsSources& sources);

}  // namespace eip2mqtt::app::redundancy
