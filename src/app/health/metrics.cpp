#include "eip2mqtt/app/health/metrics.hpp"

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
    g.writes = sources.writes;
    if (sources.history) g.history = history_metrics(*sources.history);
    if (sources.commands) g.commands = *sources.commands;
    g.connections = connections_metrics(sources);
    return snapshot;
}

std::string status_line(const MetricsSources& sources) {
    auto line = std::to_string(sources.datagrams.datagrams) + " datagrams, " +
                std::to_string(sources.datagrams.accepted) + " accepted, " +
                std::to_string(sources.mqtt.published) + " published, MQTT " +
                (sources.mqtt.connected ? "connected" : "disconnected");
    for (const auto& more : sources.more_connections) {
        line += ", " + more.name + " " + (more.mqtt.connected ? "connected" : "disconnected");
    }
    return line;
}

namespace {

adapters::metrics::ConnectionMetrics connection_metrics(const ConnectionSources& sources) {
    adapters::metrics::ConnectionMetrics out{sources.name,         sources.mqtt.connected,
                                             sources.mqtt.broker,  sources.mqtt.published,
                                             sources.mqtt.queued,  sources.mqtt.dropped_overflow,
                                             sources.mqtt.refused, std::nullopt};
    if (sources.history) out.history = history_metrics(*sources.history);
    return out;
}

}  // namespace

std::vector<adapters::metrics::ConnectionMetrics> connections_metrics(
    const MetricsSources& sources) {
    std::vector<adapters::metrics::ConnectionMetrics> out;
    if (sources.more_connections.empty()) return out;
    out.push_back(connection_metrics({sources.mqtt_name, sources.mqtt, sources.history}));
    for (const auto& more : sources.more_connections) out.push_back(connection_metrics(more));
    return out;
}

}  // namespace eip2mqtt::app
