#include "eip2mqtt/app/status/status_module.hpp"

#include <boost/asio/post.hpp>
#include <future>
#include <string>

#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status {
namespace {

using adapters::metrics::HttpAnswer;

constexpr std::string_view exchanges_prefix = "/api/exchanges/";

HttpAnswer json_answer(std::string body) { return {200, "application/json", std::move(body)}; }

HttpAnswer unavailable() {
    return {503, "application/json",
            R"({"error":"the gateway's loop did not answer in time: it is busy or stopping"})"};
}

/// What `ask(module)` returns, asked on `loop` by a server thread that waits for it (wait at
/// most: then `late`). A module gone, or a loop that ended with the question unasked, is late.
template <typename T, typename Ask>
T on_loop(const boost::asio::any_io_executor& loop, const std::weak_ptr<StatusModule*>& self,
          Ask ask, T late) {
    auto asked = std::make_shared<std::promise<T>>();
    auto answered = asked->get_future();
    boost::asio::post(loop, [asked, self, ask = std::move(ask), late] {
        const auto module = self.lock();
        asked->set_value(module ? ask(**module) : late);
    });
    if (answered.wait_for(StatusModule::request_wait) != std::future_status::ready) return late;
    try {
        return answered.get();
    } catch (const std::future_error&) {
        return late;
    }
}

}  // namespace

StatusModule::StatusModule(const core::config::Config& config, boost::asio::any_io_executor loop,
                           const core::Clock& clock, ExchangesModule& south,
                           adapters::metrics::PrometheusEndpoint& endpoint, Sources sources)
    : loop_(std::move(loop)),
      clock_(clock),
      exchanges_(south.exchanges()),
      writes_(south.writes().write_log()),
      sparklines_(clock),
      endpoint_(endpoint),
      sources_(std::move(sources)),
      self_(std::make_shared<StatusModule*>(this)) {
    facts_.id = config.gateway.id;
    facts_.config_file = config.file;
    facts_.brokers = config.mqtt.urls;
    south.north().add(sparklines_);
}

void StatusModule::start(core::MonoTime now) {
    facts_.started_mono = now;
    facts_.started_at = facts_.loaded_at = clock_.wall();
    const std::weak_ptr<StatusModule*> self = self_;
    endpoint_.serve_pages(
        [loop = loop_, self](std::string_view path) {
            return on_loop(
                loop, self, [path = std::string(path)](StatusModule& m) { return m.answer(path); },
                std::optional(unavailable()));
        },
        [loop = loop_, self](const std::vector<std::string>& open) {
            // A page whose loop does not answer is told so, and stays open.
            return on_loop(
                loop, self, [open](StatusModule& m) { return std::optional(m.events(open)); },
                std::optional<std::string>(
                    "event: unavailable\ndata: {\"error\":\"the gateway's loop did not answer "
                    "in time\"}\n\n"));
        });
}

void StatusModule::stop() { endpoint_.serve_pages(nullptr); }

void StatusModule::apply(const core::config::Config& next) {
    facts_.config_file = next.file;
    facts_.brokers = next.mqtt.urls;
    facts_.loaded_at = clock_.wall();
    ++facts_.reloads;
    status_at_.reset();
}

const std::string& StatusModule::status_now() {
    const auto now = clock_.monotonic();
    if (!status_at_ || now - *status_at_ >= status_reuse) {
        const auto warnings = recent_warnings();
        status_ =
            status_document(facts_, sources_(), exchanges_, now, clock_.wall(), &writes_, warnings);
        status_at_ = now;
    }
    return status_;
}

std::string StatusModule::events(const std::vector<std::string>& open) {
    std::string out = "event: status\ndata: " + status_now() + "\n\n";
    const auto now = clock_.monotonic();
    const auto wall = clock_.wall();
    for (const auto& name : open) {
        if (auto document = exchange_document(exchanges_, name, now, wall, &sparklines_)) {
            out += "event: exchange\ndata: " + *document + "\n\n";
        }
    }
    return out;
}

std::optional<HttpAnswer> StatusModule::answer(std::string_view path) {
    if (path == "/api/status") return json_answer(status_now());
    if (path.starts_with(exchanges_prefix)) {
        const auto name = path.substr(exchanges_prefix.size());
        if (auto document = exchange_document(exchanges_, name, clock_.monotonic(), clock_.wall(),
                                              &sparklines_)) {
            return json_answer(std::move(*document));
        }
        return HttpAnswer{404, "application/json", R"({"error":"no such exchange"})"};
    }
    if (const auto* resource = page_resource(path)) {
        return HttpAnswer{200, std::string(resource->content_type), std::string(resource->text)};
    }
    return std::nullopt;
}

std::unique_ptr<Module> make_status_module(const core::config::Config& config,
                                           boost::asio::any_io_executor loop,
                                           const core::Clock& clock, ExchangesModule& south,
                                           adapters::metrics::PrometheusEndpoint* endpoint,
                                           StatusModule::Sources sources) {
    if (endpoint == nullptr) return nullptr;
    return std::make_unique<StatusModule>(config, std::move(loop), clock, south, *endpoint,
                                          std::move(sources));
}

}  // namespace eip2mqtt::app::status
