#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"

#include <prometheus/collectable.h>
#include <prometheus/exposer.h>
#include <prometheus/metric_family.h>

#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "adapters/metrics/detail/connection_families.hpp"
#include "adapters/metrics/detail/families.hpp"
#include "adapters/metrics/detail/listener_routes.hpp"
#include "adapters/metrics/detail/tls_front.hpp"

namespace eip2mqtt::adapters::metrics {
namespace {

using detail::family;
using detail::sample;
using prometheus::ClientMetric;
using prometheus::MetricFamily;
using prometheus::MetricType;

constexpr std::array<std::string_view, 5> consume_states{"waiting", "ok", "stale",
                                                         "signature_mismatch", "length_mismatch"};
constexpr std::array<std::string_view, 2> produce_states{"producing", "paused"};
constexpr std::array<std::string_view, 3> clock_states{"none", "synced", "unsynced"};

std::vector<ClientMetric::Label> exchange_labels(const ExchangeMetrics& exchange) {
    return {{"direction", exchange.direction}, {"exchange", exchange.name}};
}

bool known(double value) { return !std::isnan(value) && value >= 0; }

/// One family per metric, a sample per exchange of the direction it applies to (both when
/// `direction` is empty).
void add_exchange_family(std::vector<MetricFamily>& out, const MetricsSnapshot& snapshot,
                         std::string name, std::string help, MetricType type,
                         std::string_view direction,
                         const std::function<double(const ExchangeMetrics&)>& value) {
    auto result = family(std::move(name), std::move(help), type);
    for (const auto& exchange : snapshot.exchanges) {
        if (!direction.empty() && exchange.direction != direction) continue;
        const double v = value(exchange);
        if (type == MetricType::Gauge && !known(v)) continue;
        result.metric.push_back(sample(type, v, exchange_labels(exchange)));
    }
    if (!result.metric.empty()) out.push_back(std::move(result));
}

void add_reason_family(std::vector<MetricFamily>& out, std::string name, std::string help,
                       const std::map<std::string, std::uint64_t>& counts) {
    auto result = family(std::move(name), std::move(help), MetricType::Counter);
    for (const auto& [reason, count] : counts) {
        result.metric.push_back(
            sample(MetricType::Counter, static_cast<double>(count), {{"reason", reason}}));
    }
    if (!result.metric.empty()) out.push_back(std::move(result));
}

void add_single(std::vector<MetricFamily>& out, std::string name, std::string help, MetricType type,
                double value) {
    auto result = family(std::move(name), std::move(help), type);
    result.metric.push_back(sample(type, value));
    out.push_back(std::move(result));
}

constexpr auto counter = MetricType::Counter;
constexpr auto gauge = MetricType::Gauge;

/// A gateway-wide counter set: a family per counter, `{set}_{name}_total`, with one sample, or
/// one per key.
template <class Fields, class Counters>
void add_counter_set(std::vector<MetricFamily>& out, std::string_view set, const Fields& fields,
                     const Counters& counters) {
    const auto prefix = set.empty() ? std::string() : std::string(set) + "_";
    for (const auto& field : fields) {
        if (!field.in(core::in_prometheus)) continue;
        auto result =
            family(prefix + std::string(field.name) + "_total", std::string(field.help), counter);
        core::for_each_count(field, counters, [&](std::string_view key, std::uint64_t count) {
            std::vector<ClientMetric::Label> labels;
            if (!key.empty()) labels.push_back({std::string(field.label), std::string(key)});
            result.metric.push_back(sample(counter, static_cast<double>(count), labels));
        });
        out.push_back(std::move(result));
    }
}

/// exchange_state: one sample per state an exchange may be in, 1 for the current one.
void add_state_families(std::vector<MetricFamily>& out, const MetricsSnapshot& snapshot) {
    auto states =
        family("exchange_state", "Current state of the exchange (1) among its states", gauge);
    for (const auto& exchange : snapshot.exchanges) {
        const std::span<const std::string_view> all =
            exchange.direction == "produce" ? std::span<const std::string_view>(produce_states)
                                            : consume_states;
        bool listed = false;
        for (const auto state : all) {
            const bool current = exchange.state == state;
            listed = listed || current;
            states.metric.push_back(sample(gauge, current ? 1 : 0,
                                           {{"direction", exchange.direction},
                                            {"exchange", exchange.name},
                                            {"state", std::string(state)}}));
        }
        if (!listed) {
            states.metric.push_back(sample(gauge, 1,
                                           {{"direction", exchange.direction},
                                            {"exchange", exchange.name},
                                            {"state", exchange.state}}));
        }
    }
    if (!states.metric.empty()) out.push_back(std::move(states));
}

/// The per-exchange counters and gauges, each for the direction it applies to.
void add_exchange_counters(std::vector<MetricFamily>& out, const MetricsSnapshot& snapshot) {
    for (const auto& field : core::exchange::consume_counter_fields) {
        if (!field.in(core::in_prometheus)) continue;
        add_exchange_family(out, snapshot, "exchange_" + std::string(field.name) + "_total",
                            std::string(field.help), counter, "consume",
                            [&field](const ExchangeMetrics& e) {
                                return static_cast<double>(e.consumed.*field.member);
                            });
    }
    // clang-format off
    add_exchange_family(out, snapshot, "exchange_last_seen_age_seconds",
        "Seconds since the last accepted datagram", gauge, "consume",
        [](const ExchangeMetrics& e) { return e.last_seen_age_seconds; });
    add_exchange_family(out, snapshot, "exchange_jitter_seconds",
        "Smoothed inter-arrival jitter (RFC 3550 estimator)", gauge, "",
        [](const ExchangeMetrics& e) { return e.jitter_seconds; });
    add_exchange_family(out, snapshot, "exchange_mean_period_seconds",
        "Mean inter-arrival period", gauge, "",
        [](const ExchangeMetrics& e) { return e.mean_period_seconds; });
    // clang-format on
    for (const auto& field : core::exchange::produce_counter_fields) {
        if (!field.in(core::in_prometheus)) continue;
        add_exchange_family(out, snapshot, "exchange_" + std::string(field.name) + "_total",
                            std::string(field.help), counter, "produce",
                            [&field](const ExchangeMetrics& e) {
                                return static_cast<double>(e.produced.*field.member);
                            });
    }
    // clang-format off
    add_exchange_family(out, snapshot, "exchange_image_saved",
        "1 while the image file holds the image produced (0 while saves fail)", gauge, "produce",
        [](const ExchangeMetrics& e) { return e.image_saved ? 1.0 : 0.0; });
    // clang-format on
}

/// The producer clock of consumed exchanges: its state and its offset.
void add_clock_families(std::vector<MetricFamily>& out, const MetricsSnapshot& snapshot) {
    // The producer's clock of consumed exchanges: its state, and its offset, which may be
    // negative (so not an add_exchange_family gauge, which omits negative values as unknown).
    auto clocks = family("exchange_clock_state",
                         "Producer clock against the receive time (1) among none, synced, "
                         "unsynced",
                         gauge);
    auto offsets = family("exchange_clock_offset_seconds",
                          "Producer time minus receive time of the last stamped datagram", gauge);
    for (const auto& exchange : snapshot.exchanges) {
        if (exchange.direction != "consume") continue;
        for (const auto state : clock_states) {
            clocks.metric.push_back(sample(gauge, exchange.clock == state ? 1 : 0,
                                           {{"direction", exchange.direction},
                                            {"exchange", exchange.name},
                                            {"state", std::string(state)}}));
        }
        if (!std::isnan(exchange.clock_offset_seconds)) {
            offsets.metric.push_back(
                sample(gauge, exchange.clock_offset_seconds, exchange_labels(exchange)));
        }
    }
    if (!clocks.metric.empty()) out.push_back(std::move(clocks));
    if (!offsets.metric.empty()) out.push_back(std::move(offsets));
}

/// The gateway-wide figures.
void add_gateway_families(std::vector<MetricFamily>& out, const MetricsSnapshot& snapshot) {
    const auto& g = snapshot.gateway;
    add_single(out, "datagrams_total", "Datagrams received on the EIP socket", counter,
               static_cast<double>(g.datagrams));
    add_single(out, "datagrams_accepted_total", "Datagrams accepted by an exchange", counter,
               static_cast<double>(g.accepted));
    add_reason_family(out, "datagrams_dropped_total", "Datagrams dropped, by reason", g.dropped);
    add_single(out, "mqtt_connected", "1 while connected to the broker", gauge,
               g.mqtt_connected ? 1 : 0);
    if (!g.mqtt_broker.empty()) {
        // Info style: which of mqtt.url's brokers, as a label, so a dashboard sees a failover.
        auto broker =
            family("mqtt_broker", "1, labelled with the current connection's broker", gauge);
        broker.metric.push_back(sample(gauge, 1, {{"url", g.mqtt_broker}}));
        out.push_back(std::move(broker));
    }
    add_single(out, "mqtt_published_total", "Messages handed to the broker", counter,
               static_cast<double>(g.published));
    add_single(out, "mqtt_buffered", "Publications waiting for the broker", gauge,
               static_cast<double>(g.buffered));
    add_single(out, "mqtt_publications_dropped_total", "Publications dropped from a full buffer",
               counter, static_cast<double>(g.publications_dropped));
    add_single(out, "mqtt_publications_refused_total",
               "Publications dropped because the broker would refuse them", counter,
               static_cast<double>(g.publications_refused));
    add_counter_set(out, "", core::write::write_counter_fields, g.writes);
}

/// Store and forward's journal, when enabled.
void add_history_families(std::vector<MetricFamily>& out, const HistoryMetrics& h) {
    add_single(out, "history_entries", "Journaled entries waiting for their replay", gauge,
               static_cast<double>(h.entries));
    add_single(out, "history_bytes", "Size of the journal on disk", gauge,
               static_cast<double>(h.bytes));
    add_single(out, "history_oldest_age_seconds", "Age of the oldest journaled entry", gauge,
               h.oldest_age_seconds);
    add_single(out, "history_dropped_total",
               "Journaled entries dropped for the bound or a full disk", counter,
               static_cast<double>(h.dropped));
    add_single(out, "history_journaled_total", "Entries journaled while MQTT was down", counter,
               static_cast<double>(h.journaled));
    add_single(out, "history_replayed_total", "Journaled entries replayed and acknowledged",
               counter, static_cast<double>(h.replayed));
    add_single(out, "history_discarded_total",
               "Journaled entries not replayable: their exchange is gone or changed", counter,
               static_cast<double>(h.discarded));
    add_single(out, "history_replaying", "1 while the journal is being replayed", gauge,
               h.replaying ? 1 : 0);
}

std::vector<MetricFamily> to_families(const MetricsSnapshot& snapshot) {
    std::vector<MetricFamily> out;
    add_state_families(out, snapshot);
    add_exchange_counters(out, snapshot);
    add_clock_families(out, snapshot);
    add_gateway_families(out, snapshot);
    if (snapshot.gateway.history) add_history_families(out, *snapshot.gateway.history);
    detail::add_connection_families(out, snapshot.gateway.connections);
    if (snapshot.gateway.commands) {
        add_counter_set(out, core::command::command_counters_name,
                        core::command::command_counter_fields, *snapshot.gateway.commands);
    }
    return out;
}

}  // namespace

// Named, not anonymous: PrometheusEndpoint::Impl holds one.
namespace detail {

/// Serves the last update's snapshot, built into families on each scrape: with 1,000 exchanges,
/// families kept between scrapes held 4 MB (a label pair of strings per series), the snapshot
/// a fraction of it, and the loop no longer builds them every second for nobody.
class SnapshotCollectable : public prometheus::Collectable {
public:
    std::vector<MetricFamily> Collect() const override {
        std::shared_ptr<const MetricsSnapshot> snapshot;
        {
            std::lock_guard lock(mutex_);
            snapshot = snapshot_;
        }
        return snapshot ? to_families(*snapshot) : std::vector<MetricFamily>{};
    }

    void set(MetricsSnapshot snapshot) {
        auto next = std::make_shared<const MetricsSnapshot>(std::move(snapshot));
        std::lock_guard lock(mutex_);
        snapshot_.swap(next);
    }  // the lock is released before `next`, now holding the old snapshot, is freed

private:
    mutable std::mutex mutex_;
    std::shared_ptr<const MetricsSnapshot> snapshot_;
};

}  // namespace detail

struct PrometheusEndpoint::Impl {
    std::shared_ptr<detail::SnapshotCollectable> collectable =
        std::make_shared<detail::SnapshotCollectable>();
    std::shared_ptr<HealthState> health;
    std::unique_ptr<prometheus::Exposer> exposer;
    std::vector<int> ports;                   ///< civetweb's
    std::unique_ptr<detail::TlsFront> front;  ///< with TLS; stops before civetweb does
};

PrometheusEndpoint::PrometheusEndpoint(const std::string& listen,
                                       std::chrono::milliseconds liveness_timeout,
                                       const core::Clock& clock, const ListenerAccess& access)
    : impl_(std::make_unique<Impl>()) {
    impl_->health = std::make_shared<HealthState>(liveness_timeout, clock);
    const bool tls = !access.tls_cert.empty();
    try {
        // With TLS, civetweb listens on loopback alone, behind the front (tls_front.hpp).
        impl_->exposer = std::make_unique<prometheus::Exposer>(
            detail::server_options(tls ? "127.0.0.1:0" : listen), &detail::listener_callbacks());
        impl_->ports = impl_->exposer->GetListeningPorts();
        if (tls) {
            impl_->front = std::make_unique<detail::TlsFront>(
                listen, access.tls_cert, access.tls_key,
                static_cast<std::uint16_t>(impl_->ports.front()));
        }
    } catch (const std::exception& e) {
        // civetweb's CivetException: typically the port is taken or the address is not ours.
        throw std::runtime_error("cannot listen for metrics on " + listen + ": " + e.what());
    }
    impl_->exposer->RegisterCollectable(impl_->collectable);
    for (const int port : impl_->ports) {
        detail::register_port(port, access.authorization, impl_->health);
    }
}

PrometheusEndpoint::~PrometheusEndpoint() {
    for (const int port : impl_->ports) detail::unregister_port(port);
}

void PrometheusEndpoint::update(MetricsSnapshot snapshot) {
    impl_->health->update(snapshot, impl_->health->clock().monotonic());
    impl_->collectable->set(std::move(snapshot));
}

void PrometheusEndpoint::serve_pages(PageHandler pages, EventSource events) {
    auto shared = pages ? std::make_shared<const PageHandler>(std::move(pages)) : nullptr;
    auto stream = events ? std::make_shared<const EventSource>(std::move(events)) : nullptr;
    for (const int port : impl_->ports) detail::register_pages(port, shared, stream);
}

std::uint16_t PrometheusEndpoint::port() const {
    if (impl_->front) return impl_->front->port();
    const auto ports = impl_->exposer->GetListeningPorts();
    return ports.empty() ? 0 : static_cast<std::uint16_t>(ports.front());
}

}  // namespace eip2mqtt::adapters::metrics
