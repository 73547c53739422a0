#include "eip2mqtt/app/health/metrics_module.hpp"

#include <spdlog/spdlog.h>

#include "app/detail/secret_file.hpp"
#include "eip2mqtt/core/net/basic_auth.hpp"

namespace eip2mqtt::app {
namespace {

/// Who may read the listener: the password read now, from its credential or file.
adapters::metrics::ListenerAccess listener_access(const core::config::MetricsSection& metrics) {
    adapters::metrics::ListenerAccess access;
    if (metrics.auth) {
        const auto password =
            detail::read_secret_file(metrics.auth->password_file, "metrics.auth.password_file");
        access.authorization = core::net::basic_authorization(metrics.auth->username, password);
    }
    if (metrics.tls) {
        access.tls_cert = metrics.tls->cert;
        access.tls_key = metrics.tls->key;
    }
    return access;
}

std::unique_ptr<adapters::metrics::PrometheusEndpoint> make_endpoint(
    const core::config::Config& config, const core::Clock& clock) {
    const auto& metrics = config.metrics;
    if (metrics.listen.empty()) return nullptr;
    auto endpoint = std::make_unique<adapters::metrics::PrometheusEndpoint>(
        metrics.listen, adapters::metrics::PrometheusEndpoint::default_liveness_timeout, clock,
        listener_access(metrics));
    const auto scheme = metrics.tls ? "https" : "http";
    spdlog::info(
        "Prometheus metrics on {0}://{1}/metrics, health on {0}://{1}/healthz and /readyz, "
        "status on {0}://{1}/{2}",
        scheme, metrics.listen,
        metrics.auth ? " (all but health asking for user " + metrics.auth->username + ")" : "");
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
