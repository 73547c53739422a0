#pragma once
/// The daemon: wires the UDP receiver, the consumed exchanges and the MQTT client around one
/// loop (one io_context on one thread), plus signals, timers and systemd notifications.
/// Members are declared in dependency order so that handlers may capture `this`.

#include <array>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/state/image_persister.hpp"
#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/adapters/systemd/notifier.hpp"
#include "eip2mqtt/adapters/udp/receiver.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/datagram_router.hpp"
#include "eip2mqtt/app/exchange_consumer.hpp"
#include "eip2mqtt/app/exchange_producer.hpp"
#include "eip2mqtt/app/gateway_metrics.hpp"
#include "eip2mqtt/app/producer_scheduler.hpp"
#include "eip2mqtt/app/write_router.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/plan_diff.hpp"
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
    void on_message(adapters::mqtt::Incoming message);
    void reject_write(const WriteReply& reply, const std::string& target,
                      const core::write::WriteRejection& rejection, const std::string& detail = {});
    /// Routes the `set` topics of the running exchanges (after each apply_exchanges).
    void build_write_routes();
    /// The plans of config_'s exchanges, for apply_exchanges. The exchange configs (every tag
    /// again, with the marks of its keys) served validation only: they are released here.
    std::vector<core::plan::ExchangePlan> take_plans();
    /// Builds the exchanges of `plans`, keeping running ones whose plan is unchanged, stopping
    /// removed and changed ones and clearing their retained topics that no new exchange uses.
    void apply_exchanges(std::vector<core::plan::ExchangePlan> plans, bool running);
    /// What applying `plans` does to the running exchanges (core::plan::diff_plans).
    core::plan::PlanDiff diff_running(const std::vector<core::plan::ExchangePlan>& plans) const;
    /// A new producer, opening the sending socket with the first one.
    std::unique_ptr<ExchangeProducer> make_producer(core::plan::ExchangePlan plan,
                                                    const PublishSink& sink);
    /// SIGHUP: a valid new file is applied, an invalid one refused with its errors logged.
    void reload();
    void schedule_watchdog();
    std::vector<std::string> write_subscriptions() const;
    void schedule_tick();
    void on_tick();
    void schedule_metrics();
    void publish_metrics();
    std::string status_line() const;
    void wait_signal();

    core::config::Config config_;
    PublishSettings publish_settings_;
    std::string availability_topic_;
    std::string metrics_topic_;

    boost::asio::io_context loop_;
    boost::asio::signal_set signals_;
    boost::asio::steady_timer tick_timer_;
    boost::asio::steady_timer metrics_timer_;
    boost::asio::steady_timer watchdog_timer_;
    adapters::systemd::Notifier notifier_;
    std::unique_ptr<adapters::mqtt::Client> mqtt_;
    std::vector<std::unique_ptr<ExchangeConsumer>> consumers_;
    DatagramRouter datagram_router_;
    std::unique_ptr<adapters::udp::Receiver> receiver_;
    adapters::state::ImageStore image_store_;
    std::unique_ptr<adapters::udp::Sender> sender_;
    std::unique_ptr<ProducerScheduler> production_;  ///< with sender_; drives producers_
    std::unique_ptr<adapters::state::ImagePersister> persister_;  ///< with sender_
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    WriteRouter write_router_;
    std::unique_ptr<adapters::metrics::PrometheusEndpoint> prometheus_;

    GatewayCounters counters_;
    core::MonoTime started_at_;
    core::MonoTime last_refresh_scan_;
    core::ThrottledLog rejected_write_log_;
    bool stopping_ = false;
};

}  // namespace eip2mqtt::app
