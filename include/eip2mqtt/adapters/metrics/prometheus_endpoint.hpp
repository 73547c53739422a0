#pragma once
/// The optional Prometheus endpoint (`metrics.listen`): serves GET /metrics in the text
/// exposition format from the last MetricsSnapshot it was given (prometheus-cpp's civetweb
/// server, on threads of its own), and beside it /healthz and /readyz (health.hpp) and the
/// status API (page_handler.hpp).
///
/// Metrics, all prefixed `eip2mqtt_` (counters end in `_total`):
///   exchange_state{exchange,direction,state}            gauge, 1 for the current state, 0 for
///                                                       the other states of its direction
///   exchange_{name}_total{exchange,direction}          consume counters: each of
///                                                       core::exchange::consume_counter_fields
///                                                       marked in_prometheus
///   exchange_{name}_total{exchange,direction}          produce counters: each of
///                                                       core::exchange::produce_counter_fields
///                                                       marked in_prometheus
///   exchange_image_saved{exchange,direction}            gauge, 1 while the image file holds
///                                                       the image produced (or a newer one)
///   exchange_clock_state{exchange,direction,state}      gauge, 1 for none, synced or unsynced
///   exchange_clock_offset_seconds{exchange,direction}   gauge, may be negative; absent before
///                                                       the first stamped datagram
///   exchange_last_seen_age_seconds, exchange_jitter_seconds,
///   exchange_mean_period_seconds{exchange,direction}    gauges; absent while unknown
///   datagrams_total, datagrams_accepted_total, datagrams_dropped_total{reason}
///   mqtt_connected (0/1), mqtt_broker{url} (1, the current connection's broker; absent while
///   disconnected), mqtt_published_total, mqtt_buffered, mqtt_publications_dropped_total,
///   mqtt_publications_refused_total
///   {name}_total, or {name}_total{label} per key        write counters: each of
///                                                       core::write::write_counter_fields
///                                                       marked in_prometheus
///   commands_{name}_total, or per key as above          with eip.commands enabled: each of
///                                                       core::command::command_counter_fields
///                                                       marked in_prometheus
/// Counters are the gateway's own counts, copied as they are: a reload that restarts them
/// shows as a counter reset, which Prometheus's rate() handles.

#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/metrics/page_handler.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/command/command_counters.hpp"
#include "eip2mqtt/core/exchange/consume_counters.hpp"
#include "eip2mqtt/core/exchange/produce_counters.hpp"
#include "eip2mqtt/core/write/write_counters.hpp"

namespace eip2mqtt::adapters::metrics {

/// What one exchange reports.
struct ExchangeMetrics {
    std::string name;
    std::string direction;  ///< "consume" or "produce"
    std::string state;      ///< core::exchange::ConsumeState names, or "producing"/"paused"
    // consume
    core::exchange::ConsumeCounters consumed;
    /// Seconds since the last accepted datagram; negative or NaN: never (the gauge is omitted).
    double last_seen_age_seconds = -1;
    /// Inter-arrival jitter and mean period (core::exchange::ArrivalStats); negative or NaN:
    /// unknown (omitted).
    double jitter_seconds = -1;
    double mean_period_seconds = -1;
    std::string clock = "none";  ///< core::exchange::ClockState names
    /// Producer time minus receive time of the last stamped datagram; NaN: none yet (omitted).
    double clock_offset_seconds = std::numeric_limits<double>::quiet_NaN();
    // produce
    core::exchange::ProduceCounters produced;
    bool image_saved = true;
};

/// Store and forward's journal, when enabled.
struct HistoryMetrics {
    std::uint64_t entries = 0;
    std::uint64_t bytes = 0;
    double oldest_age_seconds = 0;  ///< 0 when empty
    std::uint64_t dropped = 0;      ///< for the bound or a full disk
    std::uint64_t journaled = 0;
    std::uint64_t replayed = 0;
    std::uint64_t discarded = 0;  ///< their exchange gone or changed
    bool replaying = false;
};

/// One MQTT connection's figures, with several (`mqtt` as a list).
struct ConnectionMetrics {
    std::string name;
    bool connected = false;
    std::string broker;  ///< the current broker's URL; empty while none
    std::uint64_t published = 0;
    std::uint64_t buffered = 0;
    std::uint64_t publications_dropped = 0;
    std::uint64_t publications_refused = 0;
    std::optional<HistoryMetrics> history;  ///< with its store and forward
};

/// What the gateway as a whole reports.
struct GatewayMetrics {
    std::uint64_t datagrams = 0;  ///< received on the EIP socket
    std::uint64_t accepted = 0;
    std::map<std::string, std::uint64_t> dropped;  ///< by core::wire::DropReason name
    bool mqtt_connected = false;
    std::string mqtt_broker;  ///< the current connection's broker URL; empty while none
    std::uint64_t published = 0;
    std::uint64_t buffered = 0;  ///< publications waiting for the broker (a gauge)
    std::uint64_t publications_dropped = 0;
    std::uint64_t publications_refused = 0;  ///< ClientStats::refused
    core::write::WriteCounters writes;
    std::optional<HistoryMetrics> history;
    std::optional<core::command::CommandCounters> commands;  ///< the responder on UDP 7937
    /// Every MQTT connection, the first first, when there are several; empty with one (whose
    /// figures are the mqtt_* above).
    std::vector<ConnectionMetrics> connections;
};

/// Everything the endpoint serves, as plain values: the gateway loop fills one and hands it
/// over, so no scrape thread ever touches the loop's state.
struct MetricsSnapshot {
    std::vector<ExchangeMetrics> exchanges;
    GatewayMetrics gateway;
};

/// Who may read the listener, and over what (metrics.auth, metrics.tls): /healthz and /readyz
/// never ask for the password.
struct ListenerAccess {
    /// The `Authorization` header every other request must carry
    /// (core::net::basic_authorization); empty: none asked.
    std::string authorization;
    std::string tls_cert;  ///< PEM, intermediates after it; empty: plain HTTP
    std::string tls_key;   ///< PEM
};

class PrometheusEndpoint {
public:
    /// The loop updates about once a second; ten seconds without one is a loop that no longer
    /// turns (the unit's WatchdogSec, for the same reason).
    static constexpr std::chrono::milliseconds default_liveness_timeout{10'000};

    /// Listens on `listen` (`host:port`; port 0 picks a free one). Throws std::runtime_error
    /// naming the address when it cannot listen (a start-up error). Serves an empty page, and
    /// 503 on /healthz and /readyz, until the first update(); /healthz turns 503 again once no
    /// update() came for `liveness_timeout`, measured on `clock` (outliving the endpoint).
    explicit PrometheusEndpoint(
        const std::string& listen,
        std::chrono::milliseconds liveness_timeout = default_liveness_timeout,
        const core::Clock& clock = adapters::clock::system_clock(),
        const ListenerAccess& access = {});
    /// Stops the server; civetweb's listener polls, so this can take up to about 2 s.
    ~PrometheusEndpoint();
    PrometheusEndpoint(const PrometheusEndpoint&) = delete;
    PrometheusEndpoint& operator=(const PrometheusEndpoint&) = delete;

    /// Replaces what scrapes and health checks see. Called from the loop, about once a second;
    /// safe against concurrent scrapes (one short lock).
    void update(MetricsSnapshot snapshot);

    /// The port actually listened on.
    std::uint16_t port() const;

    /// Answers every path but /metrics, /healthz and /readyz from `pages` and streams
    /// what `events` gives (/api/events) from now on; empty handlers stop, after which a
    /// request already in them may still finish, and each stream ends within a second. Any
    /// thread.
    void serve_pages(PageHandler pages, EventSource events = nullptr);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace eip2mqtt::adapters::metrics
