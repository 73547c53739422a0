#include "eip2mqtt/app/status/status_module.hpp"

#include <boost/asio/post.hpp>
#include <future>
#include <string>

namespace eip2mqtt::app::status {
namespace {

using adapters::metrics::HttpAnswer;

constexpr std::string_view exchanges_prefix = "/api/exchanges/";

HttpAnswer json_answer(std::string body) { return {200, "application/json", std::move(body)}; }

HttpAnswer unavailable() {
    return {503, "application/json",
            R"({"error":"the gateway's loop did not answer in time: it is busy or stopping"})"};
}

}  // namespace

StatusModule::StatusModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                           const core::Clock& clock, const Exchanges& exchanges,
                           adapters::metrics::PrometheusEndpoint& endpoint, Sources sources)
    : loop_(std::move(loop)),
      clock_(clock),
      exchanges_(exchanges),
      endpoint_(endpoint),
      sources_(std::move(sources)),
      self_(std::make_shared<StatusModule*>(this)) {
    facts_.id = config.gateway.id;
    facts_.config_file = config.file;
    facts_.brokers = config.mqtt.urls;
}

void StatusModule::start(core::MonoTime now) {
    facts_.started_mono = now;
    facts_.started_at = facts_.loaded_at = clock_.wall();
    // A server thread posts the request and waits; the loop answers between two events.
    endpoint_.serve_pages([loop = loop_, self = std::weak_ptr<StatusModule*>(self_)](
                              std::string_view path) -> std::optional<HttpAnswer> {
        auto asked = std::make_shared<std::promise<std::optional<HttpAnswer>>>();
        auto answered = asked->get_future();
        boost::asio::post(loop, [asked, self, path = std::string(path)] {
            const auto module = self.lock();
            asked->set_value(module ? (*module)->answer(path) : std::optional(unavailable()));
        });
        if (answered.wait_for(request_wait) != std::future_status::ready) return unavailable();
        try {
            return answered.get();
        } catch (const std::future_error&) {  // the loop ended with the request unanswered
            return unavailable();
        }
    });
}

void StatusModule::stop() { endpoint_.serve_pages(nullptr); }

void StatusModule::apply(const core::config::Config& next) {
    facts_.config_file = next.file;
    facts_.brokers = next.mqtt.urls;
    facts_.loaded_at = clock_.wall();
    ++facts_.reloads;
}

std::optional<HttpAnswer> StatusModule::answer(std::string_view path) {
    const auto now = clock_.monotonic();
    const auto wall = clock_.wall();
    if (path == "/api/status") {
        return json_answer(status_document(facts_, sources_(), exchanges_, now, wall));
    }
    if (path.starts_with(exchanges_prefix)) {
        const auto name = path.substr(exchanges_prefix.size());
        if (auto document = exchange_document(exchanges_, name, now, wall)) {
            return json_answer(std::move(*document));
        }
        return HttpAnswer{404, "application/json", R"({"error":"no such exchange"})"};
    }
    return std::nullopt;
}

std::unique_ptr<Module> make_status_module(const core::config::Config& config,
                                           boost::asio::any_io_executor loop,
                                           const core::Clock& clock, const Exchanges& exchanges,
                                           adapters::metrics::PrometheusEndpoint* endpoint,
                                           StatusModule::Sources sources) {
    if (endpoint == nullptr) return nullptr;
    return std::make_unique<StatusModule>(config, std::move(loop), clock, exchanges, *endpoint,
                                          std::move(sources));
}

}  // namespace eip2mqtt::app::status
