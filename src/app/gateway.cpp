#include "eip2mqtt/app/gateway.hpp"

#include <spdlog/spdlog.h>

#include <boost/asio/post.hpp>
#include <csignal>
#include <filesystem>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/app/command_port/command_port.hpp"
#include "eip2mqtt/app/health/metrics_module.hpp"
#include "eip2mqtt/app/health/watchdog.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"
#include "eip2mqtt/app/redundancy/role.hpp"
#include "eip2mqtt/app/reload/reload_check.hpp"
#include "eip2mqtt/app/status/status_module.hpp"

namespace eip2mqtt::app {

Gateway::Gateway(core::config::Config config, const core::Clock& clock)
    : Gateway(std::move(config), clock,
              [](Gateway& gateway, boost::asio::io_context&, ExchangesModule*& exchanges) {
                  return gateway.compose(exchanges);
              }) {}

Gateway::Gateway(core::config::Config config, const core::Clock& clock, const Compose& compose)
    : clock_(clock),
      config_(std::move(config)),
      state_dir_(config_.gateway.state_dir,
                 {config_.gateway.id, std::filesystem::absolute(config_.file).string()}),
      signals_(loop_, SIGINT, SIGTERM, SIGHUP),
      ticker_(loop_.get_executor(), clock_),
      reloads_(loop_.get_executor(), *this, clock_) {
    modules_ = ModuleList(compose(*this, loop_, exchanges_));
    exchanges_->apply_plans(reload::take_plans(config_));
    detail::release_heap();
}

Gateway::~Gateway() = default;

std::vector<std::unique_ptr<Module>> Gateway::compose(ExchangesModule*& exchanges) {
    const auto loop = loop_.get_executor();
    // The role first: the parts it gates ask it while they are built.
    std::unique_ptr<redundancy::Role> role = redundancy::make_role(config_, loop, clock_);
    auto south =
        std::make_unique<ExchangesModule>(config_, loop, clock_, role->exchanges_options());
    auto north = northbound::make_northbounds(
        config_, {loop, clock_, *role, south->writes(), south->exchanges(), south->north()});
    role->wire({config_, north, south->writes(), south->exchanges(), south->north()});
    auto commands =
        command_port::make_command_port(config_, loop, south->exchanges(), south->writes(), clock_);
    auto metrics = std::make_unique<MetricsModule>(
        config_, loop, clock_, south->exchanges(), south->north(),
        [this] { return metrics_sources(); },
        [this](const MetricsSources& sources) { notifier_.status(status_line(sources)); });
    auto status = status::make_status_module(config_, loop, clock_, *south, metrics->endpoint(),
                                             [this] { return metrics_sources(); });
    exchanges = south.get();
    // Stopped in reverse: the inputs first, the lease before the connections it fences, the
    // gateway's main connection (its `offline`) last.
    auto modules = std::move(north.modules);
    modules.push_back(std::move(role));
    modules.push_back(std::move(south));
    modules.push_back(std::move(commands));  // null without eip.commands: the list drops it
    modules.push_back(std::move(metrics));
    modules.push_back(std::move(status));  // null without metrics.listen
    modules.push_back(std::make_unique<Watchdog>(loop, notifier_));
    return modules;
}

void Gateway::request_stop() {
    boost::asio::post(loop_, [this] { stop_loop(); });
}

void Gateway::stop_loop() {
    stopping_ = true;
    loop_.stop();
}

int Gateway::run() {
    start();
    loop_.run();

    notifier_.stopping();
    // A parse under way is given up (its result would never be applied) before anything stops.
    reloads_.stop();
    ticker_.cancel();
    spdlog::info("stopping: flushing publications and publishing offline");
    modules_.stop();
    const auto sources = metrics_sources();
    spdlog::info("stopped: {} datagrams received, {} publications made, {} still queued",
                 sources.datagrams.datagrams, sources.mqtt.published, sources.mqtt.queued);
    return 0;
}

void Gateway::start() {
    const auto now = clock_.monotonic();
    modules_.start(now);
    ticker_.start(now, [this](const TickTimes& times) { modules_.tick(times); });
    wait_signal();
    spdlog::info(
        "eip2mqtt {} listening on UDP {}:{}: {} consumed and {} produced exchange(s); MQTT {}",
        config_.gateway.id, config_.eip.bind, exchanges_->local_port(),
        exchanges_->exchanges().consumers().size(), exchanges_->exchanges().producers().size(),
        brokers_line(config_));
    // Sockets are bound and the first connection attempt is under way.
    ready();
}

MetricsSources Gateway::metrics_sources() {
    MetricsSources sources{exchanges_->exchanges().datagram_counters(),
                           exchanges_->writes().counters()};
    modules_.add_metrics(sources);
    return sources;
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
        stop_loop();
    });
}

bool Gateway::apply(ParseResult parsed, std::vector<std::string>& outcome) {
    const auto changes = reload::accept(parsed, config_, exchanges_->exchanges().running_plans());
    if (!changes) return false;
    auto& next = parsed.value();
    if (!modules_.prepare(next.config)) return false;
    set_log_level(next.config.gateway.log_level);
    modules_.apply(next.config);
    config_ = std::move(next.config);
    try {
        outcome.push_back(exchanges_->apply_plans(std::move(next.plans)));
    } catch (const std::exception& e) {
        spdlog::critical("reload failed half-way: {}; exiting for a clean restart", e.what());
        stop_loop();
        return false;
    }
    modules_.applied();
    outcome.push_back(changes->empty()
                          ? "reload: no key changed"
                          : "reload: applied " + changes->describe(core::config::ReloadRule::live));
    return true;
}

bool Gateway::changes_pending() const { return modules_.changes_pending(); }

void Gateway::publish_changes(std::size_t units) { modules_.publish_changes(units); }

core::config::PublishQueueRoom Gateway::queue_room() const {
    return modules_.queue_room().value_or(
        core::config::PublishQueueRoom{0, config_.mqtt.buffer_max_messages, true});
}

}  // namespace eip2mqtt::app
