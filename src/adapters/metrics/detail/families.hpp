#pragma once
/// Building blocks of the families the endpoint serves: prometheus-cpp's plain structs, named
/// `eip2mqtt_…`.
///
/// Module-private to src/adapters/metrics.

#include <prometheus/metric_family.h>

#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::adapters::metrics::detail {

inline prometheus::MetricFamily family(std::string name, std::string help,
                                       prometheus::MetricType type) {
    prometheus::MetricFamily result;
    result.name = "eip2mqtt_" + std::move(name);
    result.help = std::move(help);
    result.type = type;
    return result;
}

/// Labels in name order, as prometheus-cpp's own families print them.
inline prometheus::ClientMetric sample(prometheus::MetricType type, double value,
                                       std::vector<prometheus::ClientMetric::Label> labels = {}) {
    prometheus::ClientMetric metric;
    metric.label = std::move(labels);
    if (type == prometheus::MetricType::Counter) {
        metric.counter.value = value;
    } else {
        metric.gauge.value = value;
    }
    return metric;
}

}  // namespace eip2mqtt::adapters::metrics::detail
