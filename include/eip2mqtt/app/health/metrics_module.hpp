#pragma once
/// The gateway's metrics and health as a module (docs/operations.md): the metrics the
/// northbounds publish every `mqtt.metrics_interval` (the JSON tree's `_gateway/.../metrics`,
/// the Sparkplug node's metrics), and, with `metrics.listen`, the Prometheus endpoint with
/// /healthz and /readyz, refreshed once a second from the loop, so that a wedged loop turns
/// /healthz red.
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <memory>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app {

class MetricsModule final : public Module {
public:
    /// Everything the metrics are made of, asked when they are made.
    using Sources = std::function<MetricsSources()>;

    /// After each publication of the metrics, with the sources they were made of.
    using Published = std::function<void(const MetricsSources& sources)>;

    /// Listens with `metrics.listen`; throws std::exception when it cannot.
    MetricsModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                  const core::Clock& clock, const Exchanges& exchanges, Northbound& north,
                  Sources sources, Published published);

    void start(core::MonoTime now) override;
    void tick(const TickTimes& times) override;
    void stop() override { timer_.cancel(); }
    /// The listener of `metrics.listen`; null without one.
    adapters::metrics::PrometheusEndpoint* endpoint() { return prometheus_.get(); }
    /// A new interval applies at once: the wait under way was for the old one.
    void apply(const core::config::Config& next) override;

private:
    void schedule();
    void publish();

    const core::Clock& clock_;
    const Exchanges& exchanges_;
    Northbound& north_;
    Sources sources_;
    Published published_;
    std::chrono::seconds interval_;
    boost::asio::steady_timer timer_;
    std::unique_ptr<adapters::metrics::PrometheusEndpoint> prometheus_;  ///< with metrics.listen
    core::MonoTime started_at_{};
};

}  // namespace eip2mqtt::app
