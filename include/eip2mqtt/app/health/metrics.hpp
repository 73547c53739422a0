#pragma once
/// The gateway's metrics, built from its counters alone: the figures by name that the metrics
/// topic (app/northbound/json_tree/json_tree_payload) and Prometheus report, and the snapshot
/// Prometheus serves. Pure: no socket, no clock of its own, so each figure can be checked
/// without running a gateway.

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/app/exchanges/datagram_router.hpp"
#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/app/exchanges/write_reply.hpp"
#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_stats.hpp"
#include "eip2mqtt/app/redundancy/pair_counters.hpp"
#include "eip2mqtt/core/command/command_counters.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/write_counters.hpp"

namespace eip2mqtt::app {

using core::write::WriteCounters;

/// Everything the metrics are made of, borrowed for one call.
/// The figures of one MQTT connection after the first (`mqtt` as a list).
struct ConnectionSources {
    std::string name;
    adapters::mqtt::ClientStats mqtt;
    const history::HistoryStats* history = nullptr;  ///< with its store and forward
};

struct MetricsSources {
    const DatagramCounters& datagrams;
    const WriteCounters& writes;
    /// The gateway's main connection (the JSON tree's), taken when the metrics are made.
    adapters::mqtt::ClientStats mqtt;
    const history::HistoryStats* history = nullptr;                    ///< with store and forward
    const northbound::sparkplug::SparkplugStats* sparkplug = nullptr;  ///< with `sparkplug:`
    const core::command::CommandCounters* commands = nullptr;       ///< with eip.commands enabled
    const redundancy::PairImageCounters* pair_images = nullptr;     ///< with `redundancy:`
    const redundancy::PairHistoryCounters* pair_history = nullptr;  ///< with pair_images
    const redundancy::PairWriteCounters* pair_writes = nullptr;     ///< with pair_images
    const redundancy::UnitRole* role = nullptr;  ///< with `redundancy:`: its state, for the page
    /// The connections after the first, in the order of `mqtt`.
    std::vector<ConnectionSources> more_connections = {};
    std::string mqtt_name = "mqtt";  ///< the main connection's name (core::config::connection_name)
};

/// The one line systemd shows for the service (sd_notify STATUS=): datagrams, publications and
/// the main connection.
std::string status_line(const MetricsSources& sources);

/// Every MQTT connection's figures, the first first, when there are several (for Prometheus,
/// /readyz and the status page); empty with one, whose figures are the gateway's own.
std::vector<adapters::metrics::ConnectionMetrics> connections_metrics(
    const MetricsSources& sources);

/// Store and forward's figures for Prometheus and the metrics topic.
adapters::metrics::HistoryMetrics history_metrics(const history::HistoryStats& stats);

/// Drops by reason name, every reason listed, for the metrics topic and Prometheus alike.
std::map<std::string, std::uint64_t> drops_by_name(const DatagramCounters& counters);

/// Gateway and per-exchange figures for Prometheus, ages taken at `now`.
adapters::metrics::MetricsSnapshot metrics_snapshot(
    const MetricsSources& sources, std::span<const std::unique_ptr<ExchangeConsumer>> consumers,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, core::MonoTime now);

}  // namespace eip2mqtt::app
