#pragma once
/// The edge node's own metrics (docs/sparkplug.md): `bdSeq` and `Node Control/Rebirth` first,
/// as Sparkplug B 3.0 requires, then the gateway's counters, those of its writes and the node's
/// (SparkplugStats), then each exchange's state and counters. Each is listed by name in the
/// NBIRTH with its index as alias, and sent by alias in an NDATA when it changed.
///
/// Pure: the caller publishes the payloads it fills. Threading: the loop only.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_stats.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

class NodeMetrics {
public:
    /// The fixed metrics, every counter 0.
    NodeMetrics();

    /// Those of the running exchanges, instead of the last ones: consumed first, then
    /// produced, each its `state` and counters.
    void exchanges_changed(const ExchangeSet& running);
    void consumed_status(const ConsumedStatus& status);
    void produced_status(const core::plan::ExchangePlan& exchange, const ProducedStatus& status);
    void gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime);
    void stats(const SparkplugStats& stats);

    /// Every metric, by name and alias, `bd_seq` the first, into `payload` for an NBIRTH;
    /// none is changed after it.
    void fill_birth(adapters::sparkplug::Payload& payload, std::uint8_t bd_seq,
                    std::uint64_t now_ms);
    /// Those changed since the last fill, by alias, into `payload` for an NDATA (no metric:
    /// nothing changed).
    void fill_changes(adapters::sparkplug::Payload& payload, std::uint64_t now_ms);

    /// Every counter at its largest and every state at its longest (sparkplug_birth_sizes).
    void widen_for_sizing();

private:
    struct Metric {
        std::string name;
        adapters::sparkplug::DataType type;
        adapters::sparkplug::MetricValue value;
        bool changed = false;  ///< set since the last NBIRTH or NDATA
        /// What the last NBIRTH or NDATA said: a value set away and back between two NDATA
        /// is no change to report.
        adapters::sparkplug::MetricValue reported;
    };

    std::size_t add(const std::string& name, adapters::sparkplug::DataType type);
    std::size_t index(const std::string& name) const { return of_name_.at(name); }
    void set(std::size_t index, adapters::sparkplug::MetricValue value);

    std::vector<Metric> metrics_;
    std::unordered_map<std::string, std::size_t> of_name_;
};

}  // namespace eip2mqtt::app::northbound::sparkplug
