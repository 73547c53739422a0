#include "eip2mqtt/app/gateway_metrics.hpp"

#include <algorithm>

namespace eip2mqtt::app {
namespace {

adapters::metrics::ExchangeMetrics consumer_metrics(const ExchangeConsumer& consumer,
                                                    core::MonoTime now) {
    adapters::metrics::ExchangeMetrics m;
    m.name = consumer.plan().spec.name;
    m.direction = "consume";
    m.state = std::string(core::exchange::to_string(consumer.exchange().state()));
    m.consumed = consumer.exchange().counters();
    m.clock = std::string(core::exchange::to_string(consumer.clock().state()));
    if (const auto offset = consumer.clock().offset_ms()) {
        m.clock_offset_seconds = static_cast<double>(*offset) / 1000.0;
    }
    if (const auto last = consumer.exchange().last_accepted()) {
        m.last_seen_age_seconds = std::chrono::duration<double>(now - *last).count();
    }
    const auto& arrivals = consumer.arrivals();
    if (arrivals.count() >= 2) {
        m.jitter_seconds = arrivals.jitter().count();
        if (const auto mean = arrivals.mean_period()) m.mean_period_seconds = mean->count();
    }
    return m;
}

adapters::metrics::ExchangeMetrics producer_metrics(const ExchangeProducer& producer) {
    adapters::metrics::ExchangeMetrics m;
    m.name = producer.plan().spec.name;
    m.direction = "produce";
    m.state = producer.paused() ? "paused" : "producing";
    m.produced = producer.counters();
    m.image_saved = producer.saved();
    return m;
}

}  // namespace

std::map<std::string, std::uint64_t> drops_by_name(const DatagramCounters& counters) {
    std::map<std::string, std::uint64_t> out;
    for (const auto reason : core::wire::all_drop_reasons) {
        out[std::string(core::wire::to_string(reason))] = counters.dropped_for(reason);
    }
    return out;
}

std::map<std::string, std::uint64_t> rejections_by_name(const WriteCounters& counters) {
    std::map<std::string, std::uint64_t> out;
    for (std::size_t i = 0; i < core::write::write_error_count; ++i) {
        out[std::string(core::write::to_string(static_cast<core::write::WriteError>(i)))] =
            counters.writes_rejected[i];
    }
    return out;
}

std::map<std::string, std::uint64_t> writes_by_origin(const WriteCounters& counters) {
    std::map<std::string, std::uint64_t> out;
    for (const auto origin : all_write_origins) {
        out[std::string(to_string(origin))] =
            counters.writes_by_origin[static_cast<std::size_t>(origin)];
    }
    return out;
}

adapters::metrics::CommandMetrics command_metrics(const CommandCounters& counters) {
    adapters::metrics::CommandMetrics c;
    for (std::size_t i = 0; i < command_request_types.size(); ++i) {
        auto name = std::string(core::command::to_string(command_request_types[i]));
        name.resize(name.size() - std::string_view("_request").size());
        c.requests[name] = counters.requests[i];
    }
    c.errors = counters.errors;
    c.refused = counters.refused;
    c.dropped = counters.dropped;
    for (const auto error : core::command::all_decode_errors) {
        if (!core::command::nak_code(error)) continue;
        c.naks[std::string(core::command::to_string(error))] =
            counters.naks[static_cast<std::size_t>(error)];
    }
    c.ignored = counters.ignored;
    return c;
}

adapters::metrics::HistoryMetrics history_metrics(const history::HistoryStats& stats) {
    adapters::metrics::HistoryMetrics h;
    h.entries = stats.journal.entries;
    h.bytes = stats.journal.bytes;
    if (stats.journal.oldest_timestamp_ms) {
        h.oldest_age_seconds = std::max<double>(
            0,
            static_cast<double>(stats.taken_at_ms - *stats.journal.oldest_timestamp_ms) / 1000.0);
    }
    h.dropped = stats.journal.dropped;
    h.journaled = stats.journaled;
    h.replayed = stats.replayed;
    h.discarded = stats.discarded;
    h.replaying = stats.replaying;
    return h;
}

adapters::metrics::MetricsSnapshot metrics_snapshot(
    const MetricsSources& sources, std::span<const std::unique_ptr<ExchangeConsumer>> consumers,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, core::MonoTime now) {
    adapters::metrics::MetricsSnapshot snapshot;
    snapshot.exchanges.reserve(consumers.size() + producers.size());
    for (const auto& consumer : consumers) {
        snapshot.exchanges.push_back(consumer_metrics(*consumer, now));
    }
    for (const auto& producer : producers)
        snapshot.exchanges.push_back(producer_metrics(*producer));
    auto& g = snapshot.gateway;
    g.datagrams = sources.datagrams.datagrams;
    g.accepted = sources.datagrams.accepted;
    g.dropped = drops_by_name(sources.datagrams);
    g.mqtt_connected = sources.mqtt.connected;
    g.mqtt_broker = sources.mqtt.broker;
    g.published = sources.mqtt.published;
    g.buffered = sources.mqtt.queued;
    g.publications_dropped = sources.mqtt.dropped_overflow;
    g.publications_refused = sources.mqtt.refused;
    g.writes_ok = sources.writes.writes_ok;
    g.writes_cancelled = sources.writes.writes_cancelled;
    g.writes_rejected = rejections_by_name(sources.writes);
    g.writes_not_saved = sources.writes.image_saves.writes_not_saved;
    g.writes_sent_unsaved = sources.writes.image_saves.writes_sent_unsaved;
    g.image_save_failures = sources.writes.image_saves.failures;
    g.writes_by_origin = writes_by_origin(sources.writes);
    if (sources.history) {
        g.history = history_metrics(*sources.history);
    }
    if (sources.commands) g.commands = command_metrics(*sources.commands);
    return snapshot;
}

}  // namespace eip2mqtt::app
