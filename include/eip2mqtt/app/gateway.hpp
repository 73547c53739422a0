#pragma once
/// The daemon: wires the UDP receiver, the exchanges, the northbounds (the JSON topic tree) and
/// the MQTT client around one loop (one io_context on one thread), plus signals, timers and
/// systemd notifications. The writes the northbounds decode go to its WriteDispatcher.
/// Members are declared in dependency order so that handlers may capture `this`.

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/state/state_dir_lock.hpp"
#include "eip2mqtt/adapters/systemd/notifier.hpp"
#include "eip2mqtt/adapters/udp/receiver.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/health/loop_watch.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"
#include "eip2mqtt/app/redundancy/pair.hpp"
#include "eip2mqtt/app/reload/reload_sequence.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::app {

class Gateway final : private reload::ReloadTarget {
public:
    /// Builds every adapter from a validated configuration; throws std::exception on start-up
    /// failures (a port that cannot be bound, an unreadable password file). Every part reads
    /// the time from `clock`.
    explicit Gateway(core::config::Config config,
                     const core::Clock& clock = adapters::clock::system_clock());
    ~Gateway();

    /// Runs until SIGTERM or SIGINT, then stops cleanly; returns the exit status.
    int run();

    /// Stops the loop from any thread (tests, signal handling).
    void request_stop();

private:
    void start();
    void on_connected();
    /// With `sparkplug:`, the edge node on its own connection (gateway_sparkplug.cpp).
    void make_sparkplug();
    /// With `mqtt.store_and_forward`: the journal and what journals and replays it
    /// (gateway_history.cpp). A journal that cannot be opened is logged; the gateway runs
    /// without it.
    void make_history();
    /// The Sparkplug node's history goes through store and forward too, on its own connection.
    void add_sparkplug_history();
    /// Runs `event` (the node's connection, a message or an acknowledgement for it, its tick);
    /// once the node is born by it, its replay of history starts.
    void on_sparkplug_event(bool connection, const std::function<void()>& event);
    /// The new exchanges of a reload applied, the outcome counted; returns the line that
    /// logs it once the reload is done.
    std::string apply_plans(std::vector<core::plan::ExchangePlan> plans);
    /// Every running exchange's retained state again, and the JSON tree's `_meta` topics.
    void republish_exchanges();
    // reload::ReloadTarget
    const std::string& file() const override { return config_.file; }
    void reloading() override { notifier_.reloading(); }
    /// A valid new file is applied whole, or refused whole (errors, or a change that needs a
    /// restart: core::config::plan_reload), the log naming each changed key. Leaves the
    /// publications of the change (retained topics cleared, new descriptions) to
    /// publish_changes.
    bool apply(ParseResult parsed, std::vector<std::string>& outcome) override;
    bool changes_pending() const override;
    void publish_changes(std::size_t units) override;
    core::config::PublishQueueRoom queue_room() const override;
    void ready() override { notifier_.ready(status_line()); }
    bool stopping() const override { return stopping_; }

    /// The live settings of the sections (`next` against config_, before it replaces it):
    /// multicast groups, log level, publish settings, MQTT buffers. False, with nothing
    /// changed, when the multicast groups cannot be joined.
    bool apply_settings(const core::config::Config& next);
    /// With `redundancy:`, the pair wired to the parts it gates (redundancy::Pair).
    void make_pair();
    /// With `sparkplug:`, the leader's session of the one edge node (gateway_sparkplug.cpp):
    /// opened when this unit takes the lead, with a bdSeq other than the pair's last one, ended
    /// (its NDEATH said, what waited dropped) when it steps down.
    void open_sparkplug_session(std::optional<std::uint8_t> heard_bd_seq);
    void end_sparkplug_session();
    /// An acknowledged publication of the JSON tree's connection: a pair's sample, else a
    /// journal entry of store and forward.
    void on_acknowledged(std::uint64_t token);
    /// A module the configuration makes (null: one it leaves out).
    void add(std::unique_ptr<Module> module);
    /// The figures the metrics are made of, borrowed for one call.
    MetricsSources metrics_sources(const adapters::mqtt::ClientStats& mqtt,
                                   const history::HistoryStats* history) const;
    void schedule_watchdog();
    void schedule_tick();
    void on_tick();
    void schedule_metrics();
    void publish_metrics();
    std::string status_line() const;
    void wait_signal();

    const core::Clock& clock_;
    core::config::Config config_;
    /// Taken first: a second gateway on the same state directory stops here, before it has
    /// opened a socket or a file.
    adapters::state::StateDirLock state_dir_;
    std::string availability_topic_;

    boost::asio::io_context loop_;
    boost::asio::signal_set signals_;
    boost::asio::steady_timer tick_timer_;
    LoopWatch loop_watch_;
    boost::asio::steady_timer metrics_timer_;
    boost::asio::steady_timer watchdog_timer_;
    adapters::systemd::Notifier notifier_;
    /// With `redundancy:`; before what it gates, whose connections and options ask it.
    std::unique_ptr<redundancy::Pair> pair_;
    std::unique_ptr<adapters::mqtt::Client> mqtt_;
    WriteDispatcher writes_;
    std::unique_ptr<northbound::json_tree::JsonTree> json_tree_;
    /// With `sparkplug:`, the edge node and its own connection (its will is the NDEATH); in a
    /// pair, connected only while this unit leads.
    std::unique_ptr<adapters::mqtt::Client> sparkplug_mqtt_;
    /// In a pair, between the node and its connection: nothing passes unless this unit leads.
    std::unique_ptr<adapters::mqtt::Publisher> sparkplug_leader_;
    std::unique_ptr<northbound::sparkplug::SparkplugNode> sparkplug_;
    std::unique_ptr<history::StoreAndForward> history_;  ///< with mqtt.store_and_forward
    northbound::FanOut northbound_;  ///< every northbound: what the exchanges report to
    Exchanges exchanges_;
    std::unique_ptr<adapters::udp::Receiver> receiver_;
    /// The modules, in dependency order: started and ticked in it, stopped in reverse.
    std::vector<std::unique_ptr<Module>> modules_;
    std::unique_ptr<adapters::metrics::PrometheusEndpoint> prometheus_;

    core::MonoTime started_at_;
    core::MonoTime last_refresh_scan_;
    bool stopping_ = false;
    /// Last: its worker's thread is stopped and joined first when the gateway dies, before
    /// anything its results reach (they are posted to the loop).
    reload::ReloadSequence reloads_;
};

}  // namespace eip2mqtt::app
