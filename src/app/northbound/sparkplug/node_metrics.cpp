// The edge node's metrics: registered once in the order of the NBIRTH, set from the gateway's
// reports, sent whole in births and by change in NDATA.

#include "eip2mqtt/app/northbound/sparkplug/node_metrics.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string_view>

#include "eip2mqtt/app/health/metrics.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using adapters::sparkplug::DataType;
using adapters::sparkplug::MetricValue;
using core::plan::Value;

/// Node metric 0 and 1, in every NBIRTH (Sparkplug B 3.0 requires them).
constexpr std::size_t bd_seq_metric = 0;
constexpr std::size_t rebirth_metric = 1;
constexpr std::array<const char*, 4> gateway_counters{"Gateway/uptime_s", "Gateway/datagrams",
                                                      "Gateway/accepted", "Gateway/dropped"};
constexpr std::array<const char*, 4> node_counters{
    "Sparkplug/births_refused", "Sparkplug/data_refused", "Sparkplug/rebirth_requests",
    "Sparkplug/node_births"};

constexpr std::size_t write_metric_count() {
    std::size_t count = 0;
    for (const auto& field : core::write::write_counter_fields) {
        if (field.in(core::in_sparkplug)) ++count;
    }
    return count;
}

/// bdSeq, Rebirth, the gateway's counters, those of its writes and the node's (SparkplugStats);
/// each exchange's metrics follow.
constexpr std::size_t fixed_metrics =
    2 + gateway_counters.size() + write_metric_count() + node_counters.size();

std::string write_metric_name(const core::write::WriteCounterField& field) {
    return "Gateway/" + std::string(field.name);
}

std::uint64_t sum(std::span<const std::uint64_t> values) {
    std::uint64_t total = 0;
    for (const auto v : values) total += v;
    return total;
}

Value counter(std::uint64_t value) { return Value{value}; }

std::string exchange_base(const core::plan::ExchangePlan& exchange) {
    return "Exchanges/" + exchange.spec.name + "/";
}

/// A node metric's alias is its place in the NBIRTH, but for `Node Control/Rebirth`: Sparkplug B
/// 3.0 forbids an alias on it, so that a host may always ask for a rebirth by its name, even one
/// that lost the aliases.
std::optional<std::uint64_t> alias_of(std::size_t index) {
    if (index == rebirth_metric) return std::nullopt;
    return index;
}

}  // namespace

NodeMetrics::NodeMetrics() {
    add("bdSeq", DataType::int64);
    add("Node Control/Rebirth", DataType::boolean);
    set(rebirth_metric, Value{false});
    for (const auto* name : gateway_counters) set(add(name, DataType::uint64), counter(0));
    for (const auto& field : core::write::write_counter_fields) {
        if (!field.in(core::in_sparkplug)) continue;
        set(add(write_metric_name(field), DataType::uint64), counter(0));
    }
    for (const auto* name : node_counters) set(add(name, DataType::uint64), counter(0));
}

std::size_t NodeMetrics::add(const std::string& name, DataType type) {
    const auto [it, added] = of_name_.emplace(name, metrics_.size());
    if (added) {
        MetricValue initial =
            type == DataType::string ? MetricValue{std::string()} : MetricValue{counter(0)};
        auto reported = initial;
        metrics_.push_back({name, type, std::move(initial), false, std::move(reported)});
    }
    return it->second;
}

void NodeMetrics::set(std::size_t index, MetricValue value) {
    auto& metric = metrics_[index];
    if (metric.value == value) return;
    metric.value = std::move(value);
    metric.changed = true;
}

void NodeMetrics::exchanges_changed(const ExchangeSet& running) {
    // Those of exchanges are rebuilt; the NBIRTH that follows lists them all again.
    metrics_.resize(fixed_metrics);
    std::erase_if(of_name_, [](const auto& entry) { return entry.second >= fixed_metrics; });
    const auto add_exchange = [&](const core::plan::ExchangePlan& plan, const auto& fields) {
        const auto base = exchange_base(plan);
        add(base + "state", DataType::string);
        for (const auto& field : fields) {
            if (field.in(core::in_sparkplug)) {
                add(base + std::string(field.name), DataType::uint64);
            }
        }
    };
    for (const auto* plan : running.consumed) {
        add_exchange(*plan, core::exchange::consume_counter_fields);
    }
    for (const auto* plan : running.produced) {
        add_exchange(*plan, core::exchange::produce_counter_fields);
    }
}

void NodeMetrics::consumed_status(const ConsumedStatus& status) {
    const auto base = exchange_base(status.exchange);
    const auto& counters = status.state.counters();
    set(index(base + "state"), std::string(core::exchange::to_string(status.state.state())));
    for (const auto& field : core::exchange::consume_counter_fields) {
        if (field.in(core::in_sparkplug)) {
            set(index(base + std::string(field.name)), counter(counters.*field.member));
        }
    }
}

void NodeMetrics::produced_status(const core::plan::ExchangePlan& exchange,
                                  const ProducedStatus& status) {
    const auto base = exchange_base(exchange);
    set(index(base + "state"), std::string(status.paused ? "paused" : "producing"));
    for (const auto& field : core::exchange::produce_counter_fields) {
        if (field.in(core::in_sparkplug)) {
            set(index(base + std::string(field.name)), counter(status.counters.*field.member));
        }
    }
}

void NodeMetrics::gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) {
    set(index("Gateway/uptime_s"), counter(static_cast<std::uint64_t>(uptime.count())));
    set(index("Gateway/datagrams"), counter(sources.datagrams.datagrams));
    set(index("Gateway/accepted"), counter(sources.datagrams.accepted));
    set(index("Gateway/dropped"), counter(sum(sources.datagrams.dropped)));
    for (const auto& field : core::write::write_counter_fields) {
        if (!field.in(core::in_sparkplug)) continue;
        set(index(write_metric_name(field)), counter(core::total(field, sources.writes)));
    }
}

void NodeMetrics::stats(const SparkplugStats& stats) {
    set(index(node_counters[0]), counter(stats.births_refused));
    set(index(node_counters[1]), counter(stats.data_refused));
    set(index(node_counters[2]), counter(stats.rebirth_requests));
    set(index(node_counters[3]), counter(stats.node_births));
}

void NodeMetrics::fill_birth(adapters::sparkplug::Payload& payload, std::uint8_t bd_seq,
                             std::uint64_t now_ms) {
    set(bd_seq_metric, Value{std::int64_t{bd_seq}});
    payload.metrics.clear();
    for (std::size_t i = 0; i < metrics_.size(); ++i) {
        auto& metric = metrics_[i];
        payload.metrics.push_back(
            {metric.name, alias_of(i), now_ms, metric.type, metric.value, false, {}});
        metric.changed = false;
        metric.reported = metric.value;
    }
}

void NodeMetrics::fill_changes(adapters::sparkplug::Payload& payload, std::uint64_t now_ms) {
    payload.metrics.clear();
    for (std::size_t i = 0; i < metrics_.size(); ++i) {
        auto& metric = metrics_[i];
        if (!metric.changed) continue;
        metric.changed = false;
        if (metric.value == metric.reported) continue;
        metric.reported = metric.value;
        const auto alias = alias_of(i);
        payload.metrics.push_back({alias ? std::string() : metric.name,
                                   alias,
                                   now_ms,
                                   metric.type,
                                   metric.value,
                                   false,
                                   {}});
    }
}

void NodeMetrics::widen_for_sizing() {
    for (auto& metric : metrics_) {
        if (metric.type == DataType::uint64) {
            metric.value = Value{std::numeric_limits<std::uint64_t>::max()};
        } else if (metric.type == DataType::string) {
            metric.value = std::string(
                core::exchange::to_string(core::exchange::ConsumeState::signature_mismatch));
        }
    }
}

}  // namespace eip2mqtt::app::northbound::sparkplug
