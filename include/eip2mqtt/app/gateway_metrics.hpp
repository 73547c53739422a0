#pragma once
/// The gateway's metrics, built from its counters alone: the figures by name that the metrics
/// topic (app/northbound/json_tree/json_tree_payload) and Prometheus report, and the snapshot
/// Prometheus serves. Pure: no socket, no clock of its own, so each figure can be checked
/// without running a gateway.

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/app/command_counters.hpp"
#include "eip2mqtt/app/datagram_router.hpp"
#include "eip2mqtt/app/exchange_consumer.hpp"
#include "eip2mqtt/app/exchange_producer.hpp"
#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_stats.hpp"
#include "eip2mqtt/app/redundancy/pair_images.hpp"
#include "eip2mqtt/app/write_reply.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app {

/// What the gateway counts of the writes it handles.
struct WriteCounters {
    std::uint64_t writes_ok = 0;  ///< writes staged for production
    std::array<std::uint64_t, core::write::write_error_count> writes_rejected{};
    /// Of writes_ok, those still queued when a reload changed or removed their exchange:
    /// answered `"reloaded"`, never produced.
    std::uint64_t writes_cancelled = 0;
    /// Writes a standby of a pair dropped unanswered, because its live leader answers them.
    std::uint64_t writes_left_to_leader = 0;
    /// Image saves of every produced exchange, and the writes whose save failed.
    ImageSaveTotals image_saves;
    /// Of writes_ok, by the protocol they came by (WriteOrigin).
    std::array<std::uint64_t, write_origin_count> writes_by_origin{};
};

/// Everything the metrics are made of, borrowed for one call.
struct MetricsSources {
    const DatagramCounters& datagrams;
    const WriteCounters& writes;
    const adapters::mqtt::ClientStats& mqtt;
    const history::HistoryStats* history = nullptr;                    ///< with store and forward
    const northbound::sparkplug::SparkplugStats* sparkplug = nullptr;  ///< with `sparkplug:`
    const CommandCounters* commands = nullptr;                   ///< with eip.commands enabled
    const redundancy::PairImageCounters* pair_images = nullptr;  ///< with `redundancy:`
};

/// Store and forward's figures for Prometheus and the metrics topic.
adapters::metrics::HistoryMetrics history_metrics(const history::HistoryStats& stats);

/// Drops by reason name, every reason listed, for the metrics topic and Prometheus alike.
std::map<std::string, std::uint64_t> drops_by_name(const DatagramCounters& counters);

/// Write rejections by error name, every error listed.
std::map<std::string, std::uint64_t> rejections_by_name(const WriteCounters& counters);

/// Accepted writes by origin name, every origin listed.
std::map<std::string, std::uint64_t> writes_by_origin(const WriteCounters& counters);

/// The command responder's figures for Prometheus and the metrics topic.
adapters::metrics::CommandMetrics command_metrics(const CommandCounters& counters);

/// Gateway and per-exchange figures for Prometheus, ages taken at `now`.
adapters::metrics::MetricsSnapshot metrics_snapshot(
    const MetricsSources& sources, std::span<const std::unique_ptr<ExchangeConsumer>> consumers,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, core::MonoTime now);

}  // namespace eip2mqtt::app
