#include "eip2mqtt/app/health/metrics_module.hpp"

#include <spdlog/spdlog.h>

namespace eip2mqtt::app {
namespace {

std::unique_ptr<adapters::metrics::PrometheusEndpoint> make_endpoint(
    const core::config::Config& config, const core::Clock& clock) {
    if (config.metrics.listen.empty()) return nullptr;
    auto endpoint = std::make_unique<adapters::metrics::PrometheusEndpoint>(
        config.metrics.listen, adapters::metrics::PrometheusEndpoint::default_liveness_timeout,
        clock);
    spdlog::info(
        "Prometheus metrics on http://{0}/metrics, health on http://{0}/healthz and /readyz, "
        "status on http://{0}/api/status",
        config.metrics.listen);
    return endpoint;
}

}  // namespace

MetricsModule::MetricsModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                             const core::Clock& clock, const Exchanges& exchanges,
                             Northbound& north, Sources sources, Published published)
    : clock_(clock),
      exchanges_(exchanges),
      north_(north),
      sources_(std::move(sources)),
      published_(std::move(published)),
      interval_(config.mqtt.metrics_interval),
      timer_(std::move(loop)),
      prometheus_(make_endpoint(config, clock)) {}

void MetricsModule::start(core::MonoTime now) {
    started_at_ = now;
    schedule();
}

void MetricsModule::tick(const TickTimes& times) {
    if (!times.refresh_scan || !prometheus_) return;
    prometheus_->update(
        metrics_snapshot(sources_(), exchanges_.consumers(), exchanges_.producers(), times.now));
}

void MetricsModule::apply(const core::config::Config& next) {
    if (next.mqtt.metrics_interval == interval_) return;
    interval_ = next.mqtt.metrics_interval;
    schedule();
}

void MetricsModule::schedule() {
    timer_.expires_after(interval_);
    timer_.async_wait([this](const boost::system::error_code& error) {
        if (error) return;
        publish();
        schedule();
    });
}

void MetricsModule::publish() {
    const auto uptime =
        std::chrono::duration_cast<std::chrono::seconds>(clock_.monotonic() - started_at_);
    const auto sources = sources_();
    north_.gateway_metrics(sources, uptime);
    published_(sources);
}

}  // namespace eip2mqtt::app
