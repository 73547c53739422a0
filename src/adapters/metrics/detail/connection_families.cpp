#include "adapters/metrics/detail/connection_families.hpp"

#include <functional>
#include <string>

#include "adapters/metrics/detail/families.hpp"

namespace eip2mqtt::adapters::metrics::detail {
namespace {

using prometheus::MetricType;

/// A family with a sample per connection that has the figure (`value` returns nullopt
/// otherwise); none when no connection has it.
void add_family(std::vector<prometheus::MetricFamily>& out,
                std::span<const ConnectionMetrics> connections, std::string name, std::string help,
                MetricType type,
                const std::function<std::optional<double>(const ConnectionMetrics&)>& value) {
    auto result = family("connection_" + std::move(name), std::move(help), type);
    for (const auto& connection : connections) {
        if (const auto v = value(connection)) {
            result.metric.push_back(sample(type, *v, {{"connection", connection.name}}));
        }
    }
    if (!result.metric.empty()) out.push_back(std::move(result));
}

std::optional<double> count(std::uint64_t value) { return static_cast<double>(value); }

}  // namespace

void add_connection_families(std::vector<prometheus::MetricFamily>& out,
                             std::span<const ConnectionMetrics> connections) {
    constexpr auto counter = MetricType::Counter;
    constexpr auto gauge = MetricType::Gauge;
    // clang-format off
    add_family(out, connections, "mqtt_connected", "1 while the connection is up", gauge,
        [](const ConnectionMetrics& c) { return c.connected ? 1.0 : 0.0; });
    add_family(out, connections, "mqtt_published_total", "Messages handed to its broker",
        counter, [](const ConnectionMetrics& c) { return count(c.published); });
    add_family(out, connections, "mqtt_buffered", "Publications waiting for its broker", gauge,
        [](const ConnectionMetrics& c) { return count(c.buffered); });
    add_family(out, connections, "mqtt_publications_dropped_total",
        "Publications dropped from its full buffer", counter,
        [](const ConnectionMetrics& c) { return count(c.publications_dropped); });
    add_family(out, connections, "mqtt_publications_refused_total",
        "Publications dropped because its broker would refuse them", counter,
        [](const ConnectionMetrics& c) { return count(c.publications_refused); });
    add_family(out, connections, "history_entries", "Journaled entries waiting for their replay",
        gauge, [](const ConnectionMetrics& c) -> std::optional<double> {
            if (!c.history) return std::nullopt;
            return static_cast<double>(c.history->entries);
        });
    add_family(out, connections, "history_journaled_total", "Entries journaled while it was down",
        counter, [](const ConnectionMetrics& c) -> std::optional<double> {
            if (!c.history) return std::nullopt;
            return static_cast<double>(c.history->journaled);
        });
    add_family(out, connections, "history_replayed_total",
        "Journaled entries replayed and acknowledged", counter,
        [](const ConnectionMetrics& c) -> std::optional<double> {
            if (!c.history) return std::nullopt;
            return static_cast<double>(c.history->replayed);
        });
    add_family(out, connections, "history_dropped_total",
        "Journaled entries dropped for the bound or a full disk", counter,
        [](const ConnectionMetrics& c) -> std::optional<double> {
            if (!c.history) return std::nullopt;
            return static_cast<double>(c.history->dropped);
        });
    // clang-format on
}

}  // namespace eip2mqtt::adapters::metrics::detail
