#include "eip2mqtt/app/gateway.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/post.hpp>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <limits>
#include <memory>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/app/command_port/command_port.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/core/redundancy/acked_watermarks.hpp"
#include "eip2mqtt/core/wire/decode.hpp"

namespace eip2mqtt::app {
namespace {

using namespace std::chrono_literals;

// How often timeouts and `_status` throttling are checked: a tenth of the shortest default
// timeout in practice, and cheap (one comparison per exchange).
constexpr auto tick_interval = 10ms;
// refresh_s is counted in seconds, so the tags are scanned for it once a second.
constexpr auto refresh_scan_interval = 1s;
// How long a clean stop waits for queued publications before giving up.
constexpr auto stop_flush_timeout = 3s;

/// `options` holds what the pair sets (redundancy::Pair::exchanges_options).
ExchangesOptions exchanges_options(const core::config::Config& config, ExchangesOptions options) {
    options.sender.bind = config.eip.bind;
    options.sender.multicast_ttl = config.eip.multicast_ttl;
    options.sender.multicast_interface = config.eip.multicast_interface;
    options.port = config.eip.port;
    options.state_dir = config.gateway.state_dir;
    return options;
}

adapters::udp::ReceiverOptions receiver_options(const core::config::EipSection& eip) {
    adapters::udp::ReceiverOptions options;
    options.bind = eip.bind;
    options.port = eip.port;
    for (const auto& group : eip.multicast)
        options.multicast.push_back({group.group, group.interface});
    return options;
}

}  // namespace

Gateway::Gateway(core::config::Config config, const core::Clock& clock)
    : clock_(clock),
      config_(std::move(config)),
      state_dir_(config_.gateway.state_dir,
                 {config_.gateway.id, std::filesystem::absolute(config_.file).string()}),
      availability_topic_(config_.mqtt.base_topic + "/_gateway/" + config_.gateway.id + "/state"),
      signals_(loop_, SIGINT, SIGTERM, SIGHUP),
      tick_timer_(loop_),
      metrics_timer_(loop_),
      watchdog_timer_(loop_),
      pair_(config_.redundancy.enabled()
                ? std::make_unique<redundancy::Pair>(loop_.get_executor(), clock_)
                : nullptr),
      writes_([this](ExchangeWrite&& write, const WriteReply& reply,
                     core::MonoTime now) { return exchanges_.stage(std::move(write), reply, now); },
              clock_),
      exchanges_(
          loop_.get_executor(),
          exchanges_options(config_, pair_ ? pair_->exchanges_options() : ExchangesOptions{}),
          northbound_, writes_.image_saves()),
      reloads_(loop_.get_executor(), *this, clock_) {
    auto mqtt_options = mqtt_client_options(config_, availability_topic_);
    if (pair_) {
        // The unit's own topics (state, metrics, role) and the exchanges' `_meta` are said by
        // both units; the tree's retained values, `_values` and a takeover's `_history` replay
        // (its tokens are the pair's) by the leader alone. Store and forward's `_history` goes
        // whoever leads: each unit replays what it journaled.
        mqtt_options.may_send = pair_->may_send([gateway = config_.mqtt.base_topic + "/_gateway/"](
                                                    const adapters::mqtt::Message& m) {
            const bool leaders = m.historical ? core::redundancy::AckedWatermarks::owns(m.ack_token)
                                              : m.retain || m.batch_lane;
            return leaders && !m.topic.starts_with(gateway) && !m.topic.ends_with("/_meta");
        });
    }
    mqtt_ = std::make_unique<adapters::mqtt::Client>(loop_.get_executor(), std::move(mqtt_options));
    json_tree_ = std::make_unique<northbound::json_tree::JsonTree>(
        northbound::json_tree::json_tree_options(config_), *mqtt_, writes_);
    make_history();
    if (!config_.sparkplug.enabled() || config_.sparkplug.uns) northbound_.add(*json_tree_);
    make_sparkplug();
    make_pair();
    exchanges_.apply(reload::take_plans(config_), clock_.monotonic(), clock_.wall());

    receiver_ = std::make_unique<adapters::udp::Receiver>(loop_.get_executor(),
                                                          receiver_options(config_.eip));
    add(command_port::make_command_port(config_, loop_.get_executor(), exchanges_, writes_,
                                        clock_));
    if (!config_.metrics.listen.empty()) {
        prometheus_ =
            std::make_unique<adapters::metrics::PrometheusEndpoint>(config_.metrics.listen);
        spdlog::info(
            "Prometheus metrics on http://{0}/metrics, health on http://{0}/healthz and "
            "/readyz",
            config_.metrics.listen);
    }
    detail::release_heap();
}

Gateway::~Gateway() = default;

void Gateway::request_stop() {
    boost::asio::post(loop_, [this] {
        stopping_ = true;
        loop_.stop();
    });
}

int Gateway::run() {
    start();
    loop_.run();

    notifier_.stopping();
    // A parse under way is given up (its result would never be applied) before anything stops.
    reloads_.stop();
    spdlog::info("stopping: flushing publications and publishing offline");
    receiver_->stop();
    for (auto it = modules_.rbegin(); it != modules_.rend(); ++it) (*it)->stop();
    // The last saves reach the disk, and their write results the MQTT queue before it flushes.
    exchanges_.stop();
    // The retained topics a reload under way had yet to clear, before the connection ends.
    json_tree_->publish_changes(std::numeric_limits<std::size_t>::max());
    // Nothing is produced any more: the lease goes, its will clearing the leader topic.
    if (pair_) pair_->stop(stop_flush_timeout);
    // The edge node's NDEATH after its last data, then the JSON tree's `offline`.
    if (sparkplug_mqtt_) sparkplug_mqtt_->stop(stop_flush_timeout);
    mqtt_->stop(stop_flush_timeout);
    const auto stats = mqtt_->stats();
    spdlog::info("stopped: {} datagrams received, {} publications made, {} still queued",
                 exchanges_.datagram_counters().datagrams, stats.published, stats.queued);
    return 0;
}

void Gateway::start() {
    started_at_ = clock_.monotonic();
    last_refresh_scan_ = started_at_;
    mqtt_->set_on_connected([this] { on_connected(); });
    if (history_ || (pair_ && pair_->hears_acknowledgements())) {
        mqtt_->set_on_acknowledged([this](std::uint64_t token) { on_acknowledged(token); });
    }
    mqtt_->set_on_message(
        [this](const adapters::mqtt::Incoming& message) { json_tree_->on_message(message); });
    exchanges_.start(started_at_);
    receiver_->start(
        [this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
               bool truncated) { exchanges_.route(bytes, from, truncated, clock_.monotonic()); });
    for (auto& module : modules_) module->start(started_at_);
    mqtt_->start();
    if (pair_) pair_->start();
    if (sparkplug_mqtt_) {
        sparkplug_mqtt_->set_on_connected([this] {
            on_sparkplug_event(
                true, [this] { sparkplug_->on_connected(sparkplug_mqtt_->max_packet_size()); });
        });
        // One handler for both owners of the tokens on the node's connection: the node's own
        // NDEATH (whose acknowledgement may let a pending birth go), else a journal entry.
        sparkplug_mqtt_->set_on_acknowledged([this](std::uint64_t token) {
            on_sparkplug_event(false, [&] {
                if (!sparkplug_->on_acknowledged(token) && history_) {
                    history_->on_acknowledged(*sparkplug_, token);
                }
            });
        });
        sparkplug_mqtt_->set_on_message([this](const adapters::mqtt::Incoming& message) {
            on_sparkplug_event(false, [&] { sparkplug_->on_message(message); });
        });
        // A pair's units are one edge node: only the leader holds its session (on_role).
        if (!pair_) sparkplug_mqtt_->start();
    }
    wait_signal();
    schedule_tick();
    schedule_metrics();
    schedule_watchdog();
    spdlog::info(
        "eip2mqtt {} listening on UDP {}:{}: {} consumed and {} produced exchange(s); MQTT {}",
        config_.gateway.id, config_.eip.bind, receiver_->local_port(),
        exchanges_.consumers().size(), exchanges_.producers().size(),
        broker_list(config_.mqtt.urls));
    // Sockets are bound and the first connection attempt is under way.
    notifier_.ready(status_line());
}

void Gateway::add(std::unique_ptr<Module> module) {
    if (module) modules_.push_back(std::move(module));
}

MetricsSources Gateway::metrics_sources(const adapters::mqtt::ClientStats& mqtt,
                                        const history::HistoryStats* history) const {
    MetricsSources sources{exchanges_.datagram_counters(), writes_.counters(), mqtt, history};
    sources.sparkplug = sparkplug_ ? &sparkplug_->stats() : nullptr;
    sources.pair_images = pair_ ? &pair_->image_counters() : nullptr;
    sources.pair_history = pair_ ? pair_->history_counters() : nullptr;
    sources.pair_writes = pair_ ? &pair_->write_counters() : nullptr;
    for (const auto& module : modules_) module->add_metrics(sources);
    return sources;
}

void Gateway::make_pair() {
    if (!pair_) return;
    redundancy::SessionHooks session;
    if (sparkplug_) {
        session = {[this](std::optional<std::uint8_t> heard) { open_sparkplug_session(heard); },
                   [this] { end_sparkplug_session(); },
                   [this] { return sparkplug_->session_bd_seq(); }};
    }
    pair_->wire({config_, *mqtt_, *json_tree_, writes_, exchanges_, northbound_, std::move(session),
                 [this] { republish_exchanges(); }});
}

void Gateway::on_acknowledged(std::uint64_t token) {
    if (pair_ && pair_->on_acknowledged(token)) return;
    if (history_) history_->on_acknowledged(token);
}

void Gateway::wait_signal() {
    // Signals only reach the loop through the signal_set: handlers run here, between two
    // events, never in signal context (mosquitto's signals.c sets flags for the same reason).
    signals_.async_wait([this](const boost::system::error_code& error, int signo) {
        if (error) return;
        if (signo == SIGHUP) {
            reloads_.request();
            wait_signal();
            return;
        }
        spdlog::info("received signal {}", signo == SIGINT ? "SIGINT" : "SIGTERM");
        stopping_ = true;
        loop_.stop();
    });
}

void Gateway::schedule_watchdog() {
    const auto interval = notifier_.watchdog_interval();
    if (!interval) return;
    // Pinged from the loop that does the work: a wedged loop stops the pings and systemd
    // restarts the service.
    notifier_.watchdog();
    watchdog_timer_.expires_after(*interval);
    watchdog_timer_.async_wait([this](const boost::system::error_code& error) {
        if (!error) schedule_watchdog();
    });
}

void Gateway::on_connected() {
    spdlog::info("republishing retained state of {} exchange(s)",
                 exchanges_.consumers().size() + exchanges_.producers().size());
    republish_exchanges();
    // History goes behind the current state.
    if (history_) history_->on_connected(clock_.monotonic());
}

void Gateway::schedule_tick() {
    tick_timer_.expires_after(tick_interval);
    tick_timer_.async_wait([this](const boost::system::error_code& error) {
        if (error) return;
        loop_watch_.on_tick(tick_timer_.expiry(), clock_.monotonic());
        on_tick();
        schedule_tick();
    });
}

void Gateway::on_tick() {
    // What arrived in time is taken before any exchange is judged stale (a loop busy with
    // births or a reload may not have read it yet).
    receiver_->read_pending();
    const auto now = clock_.monotonic();
    const auto wall = clock_.wall();
    if (pair_) pair_->tick(now);
    const bool refresh_scan = now - last_refresh_scan_ >= refresh_scan_interval;
    // Before the metrics: figures showing a datagram accepted then show it journaled for good.
    if (history_) history_->on_tick(now);
    if (pair_) pair_->tick_replay();
    // A pending rebirth may be born here: the node's replay of history starts with it.
    if (sparkplug_) on_sparkplug_event(false, [&] { sparkplug_->tick(now); });
    if (refresh_scan) {
        last_refresh_scan_ = now;
        if (prometheus_) {
            const auto stats = mqtt_->stats();
            const auto history = history_ ? std::optional(history_->stats()) : std::nullopt;
            prometheus_->update(
                metrics_snapshot(metrics_sources(stats, history ? &*history : nullptr),
                                 exchanges_.consumers(), exchanges_.producers(), now));
        }
    }
    exchanges_.tick(now, wall, refresh_scan);
    json_tree_->publish_due_meta();
    for (auto& module : modules_) module->tick({now, wall, refresh_scan});
    loop_watch_.flush(now);
}

void Gateway::schedule_metrics() {
    metrics_timer_.expires_after(config_.mqtt.metrics_interval);
    metrics_timer_.async_wait([this](const boost::system::error_code& error) {
        if (error) return;
        publish_metrics();
        schedule_metrics();
    });
}

void Gateway::publish_metrics() {
    const auto stats = mqtt_->stats();
    const auto uptime =
        std::chrono::duration_cast<std::chrono::seconds>(clock_.monotonic() - started_at_);
    const auto history = history_ ? std::optional(history_->stats()) : std::nullopt;
    northbound_.gateway_metrics(metrics_sources(stats, history ? &*history : nullptr), uptime);
    notifier_.status(status_line());
}

std::string Gateway::status_line() const {
    const auto stats = mqtt_->stats();
    const auto& datagrams = exchanges_.datagram_counters();
    return std::to_string(datagrams.datagrams) + " datagrams, " +
           std::to_string(datagrams.accepted) + " accepted, " + std::to_string(stats.published) +
           " published, MQTT " + (stats.connected ? "connected" : "disconnected");
}

}  // namespace eip2mqtt::app
