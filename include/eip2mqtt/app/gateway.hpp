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

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/state/state_dir_lock.hpp"
#include "eip2mqtt/adapters/systemd/notifier.hpp"
#include "eip2mqtt/adapters/udp/command_socket.hpp"
#include "eip2mqtt/adapters/udp/receiver.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/command_port/command_responder.hpp"
#include "eip2mqtt/app/command_port/command_views.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/health/gateway_metrics.hpp"
#include "eip2mqtt/app/health/loop_watch.hpp"
#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"
#include "eip2mqtt/app/redundancy/pair.hpp"
#include "eip2mqtt/app/reload/reload_worker.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::app {

class Gateway {
public:
    /// Builds every adapter from a validated configuration; throws std::exception on start-up
    /// failures (a port that cannot be bound, an unreadable password file).
    explicit Gateway(core::config::Config config);
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
    /// The plans of `config`'s exchanges, for Exchanges::apply. The exchange configs (every tag
    /// again, with the marks of its keys) served validation only: they are released here.
    static std::vector<core::plan::ExchangePlan> take_plans(core::config::Config& config);
    /// The new exchanges of a reload applied, the outcome counted; returns the line that
    /// logs it once the reload is done.
    std::string apply_plans(std::vector<core::plan::ExchangePlan> plans);
    /// Every running exchange's retained state again, and the JSON tree's `_meta` topics.
    void republish_exchanges();
    /// SIGHUP: the file is handed to reloads_, which reads and checks it off the loop; a
    /// SIGHUP while it parses has it parsed again once that parse ends (ReloadWorker::request).
    void reload();
    /// ReloadWorker::Parse, on the worker's thread: the file loaded, its plans made.
    static ParseResult parse_reload(const std::string& path, std::stop_token stop);
    /// A parse's result, on the loop: started (start_reload), or, while another is applied,
    /// kept until that one ends.
    void on_reload_parsed(ParseResult parsed);
    /// A result and how long its parse took.
    struct ParsedReload {
        ParseResult result;
        std::chrono::steady_clock::duration parse_took;
    };
    /// Applied (apply_reload), its publications made in slices (continue_reload), then
    /// end_reload.
    void start_reload(ParsedReload parsed);
    /// A valid new file is applied whole, or refused whole (errors, or a change that needs a
    /// restart: core::config::plan_reload), the log naming each changed key. Leaves the
    /// publications of the change (retained topics cleared, new descriptions) to
    /// continue_reload.
    void apply_reload(ParseResult parsed);
    /// One slice of the reload's publications (JsonTree::publish_changes), bounded by
    /// core::config::slice_units; the next one posted, or after a tick while the publish queue
    /// is half full. Once none is left, end_reload.
    void continue_reload();
    /// The heap released, the outcome logged; READY once no other reload is under way; the
    /// next result that waited applied.
    void end_reload();
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
    /// With `eip.commands.enabled`: the command port and its responder (gateway_commands.cpp).
    void make_commands();
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
    CommandViewContext command_context_;
    std::unique_ptr<CommandResponder> commands_;                    ///< with eip.commands.enabled
    std::unique_ptr<adapters::udp::CommandSocket> command_socket_;  ///< with commands_
    std::unique_ptr<adapters::metrics::PrometheusEndpoint> prometheus_;

    core::MonoTime started_at_;
    core::MonoTime last_refresh_scan_;
    bool stopping_ = false;
    /// Results the loop still waits for from reloads_ (or has, waiting in reloads_parsed_),
    /// and when the last reload started.
    int reloads_pending_ = 0;
    core::MonoTime reload_requested_at_;
    /// The reload being applied, from its result on the loop to end_reload.
    struct ReloadApply {
        core::MonoTime applying_from;
        std::chrono::steady_clock::duration parse_took;
        std::vector<std::string> outcome;  ///< info lines, logged once it is done
        bool applied = false;              ///< the heap is released at the end
        int slices = 0;
        std::chrono::steady_clock::duration longest_slice{};
    };
    std::optional<ReloadApply> reload_apply_;
    std::deque<ParsedReload> reloads_parsed_;  ///< arrived while reload_apply_ was under way
    boost::asio::steady_timer reload_timer_;   ///< waits for the publish queue to drain
    /// Last: its thread is stopped and joined first when the gateway dies, before anything
    /// its results reach (they are posted to the loop).
    ReloadWorker reloads_;
};

}  // namespace eip2mqtt::app
