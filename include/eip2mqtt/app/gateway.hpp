#pragma once
/// The daemon's composition root: one loop (one io_context on one thread) with its signals,
/// its tick and systemd's notifications, and the modules a configuration makes, in dependency
/// order (docs/architecture.md, The house): this unit's role, the exchanges, the northbounds,
/// the command port, the metrics. It starts and ticks them in that order, stops them in reverse
/// and applies a reload to each, or to none.

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/state/state_dir_lock.hpp"
#include "eip2mqtt/adapters/systemd/notifier.hpp"
#include "eip2mqtt/app/exchanges/exchanges_module.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/health/tick_timer.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/module_list.hpp"
#include "eip2mqtt/app/reload/reload_sequence.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app {

class Gateway final : private reload::ReloadTarget {
public:
    /// The modules of `config`, made with it. Made elsewhere (tests give fake ones): `modules`
    /// from its loop, in dependency order, around the `exchanges` among them.
    using Compose = std::function<std::vector<std::unique_ptr<Module>>(
        Gateway& gateway, boost::asio::io_context& loop, ExchangesModule*& exchanges)>;

    /// Builds every module from a validated configuration; throws std::exception on start-up
    /// failures (a port that cannot be bound, an unreadable password file). Every part reads
    /// the time from `clock`.
    explicit Gateway(core::config::Config config,
                     const core::Clock& clock = adapters::clock::system_clock());
    Gateway(core::config::Config config, const core::Clock& clock, const Compose& compose);
    ~Gateway();

    /// Runs until SIGTERM or SIGINT, then stops cleanly; returns the exit status. A module
    /// that fails to start throws on (ModuleList::start).
    int run();
    /// Stops the loop from any thread (tests, signal handling).
    void request_stop();
    /// Everything the metrics are made of, now.
    MetricsSources metrics_sources();

private:
    std::vector<std::unique_ptr<Module>> compose(ExchangesModule*& exchanges);
    void start();
    void stop_loop();
    void wait_signal();
    // reload::ReloadTarget
    const std::string& file() const override { return config_.file; }
    void reloading() override { notifier_.reloading(); }
    /// A valid new file is applied to every module, or refused whole (reload::accept, or a
    /// module that cannot take it); what the change publishes is left to publish_changes.
    bool apply(ParseResult parsed, std::vector<std::string>& outcome) override;
    bool changes_pending() const override;
    void publish_changes(std::size_t units) override;
    core::config::PublishQueueRoom queue_room() const override;
    void ready() override { notifier_.ready(status_line(metrics_sources())); }
    bool stopping() const override { return stopping_; }

    const core::Clock& clock_;
    core::config::Config config_;
    /// Taken first: a second gateway on the same state directory stops here, before it has
    /// opened a socket or a file.
    adapters::state::StateDirLock state_dir_;
    boost::asio::io_context loop_;
    boost::asio::signal_set signals_;
    TickTimer ticker_;
    adapters::systemd::Notifier notifier_;
    ModuleList modules_;
    ExchangesModule* exchanges_ = nullptr;  ///< among modules_
    bool stopping_ = false;
    /// Last: its worker's thread is stopped and joined first when the gateway dies, before
    /// anything its results reach (they are posted to the loop).
    reload::ReloadSequence reloads_;
};

}  // namespace eip2mqtt::app
