#pragma once
/// The status page and its API on the metrics listener (docs/operations.md, "Status API"):
/// GET /, /api/status, /api/exchanges/{name} and the page's event stream /api/events,
/// read-only. The HTTP server's threads never touch the gateway's
/// state: each request is handed to the loop, which builds the document between two events,
/// and the thread waits for it (request_wait at most: a loop that does not answer is
/// answered 503).
///
/// Threading: the module on the loop; its page handler on the server's threads.

#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/app/exchanges/exchanges_module.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/status/sparklines.hpp"
#include "eip2mqtt/app/status/status_documents.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app::status {

class StatusModule final : public Module {
public:
    using Sources = std::function<MetricsSources()>;

    /// How long a request waits for the loop before it is answered 503.
    static constexpr std::chrono::milliseconds request_wait{2000};

    /// Serves on `endpoint` from start() to stop(). The endpoint may go before the module
    /// (the modules die in their order, the metrics first): only stop() touches it after start.
    /// It reads `south`'s exchanges and write log, and keeps the sparklines of what its
    /// fan-out reports (added to it now); `south` outlives the module's use of it.
    StatusModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                 const core::Clock& clock, ExchangesModule& south,
                 adapters::metrics::PrometheusEndpoint& endpoint, Sources sources);

    void start(core::MonoTime now) override;
    void stop() override;
    void apply(const core::config::Config& next) override;

    /// How long a status document is served again before it is built anew: ten pages open
    /// build it about once a second between them, not ten times.
    static constexpr std::chrono::milliseconds status_reuse{500};

    /// The answer to GET `path`, on the loop.
    std::optional<adapters::metrics::HttpAnswer> answer(std::string_view path);
    /// The events of a page's stream: the status, and each exchange of `open`. On the loop.
    std::string events(const std::vector<std::string>& open);

private:
    const std::string& status_now();

    boost::asio::any_io_executor loop_;
    const core::Clock& clock_;
    const Exchanges& exchanges_;
    const WriteLog& writes_;
    Sparklines sparklines_;
    adapters::metrics::PrometheusEndpoint& endpoint_;
    Sources sources_;
    GatewayFacts facts_;
    std::string status_;  ///< the last status document, built at status_at_
    std::optional<core::MonoTime> status_at_;
    /// What the handler's posted requests reach: gone with the module, so that a request
    /// still queued on the loop then finds nothing to ask.
    std::shared_ptr<StatusModule*> self_;
};

/// The status API on `endpoint` (metrics.listen's listener); null without one.
std::unique_ptr<Module> make_status_module(const core::config::Config& config,
                                           boost::asio::any_io_executor loop,
                                           const core::Clock& clock, ExchangesModule& south,
                                           adapters::metrics::PrometheusEndpoint* endpoint,
                                           StatusModule::Sources sources);

}  // namespace eip2mqtt::app::status
