#include "eip2mqtt/app/reload/reload_sequence.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/post.hpp>
#include <memory>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"

namespace eip2mqtt::app::reload {
namespace {

using namespace std::chrono_literals;

// How long a reload waits for the publish queue to drain before its next slice: a tick.
constexpr auto queue_drain_wait = 10ms;

long long ms(std::chrono::steady_clock::duration d) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

}  // namespace

std::vector<core::plan::ExchangePlan> take_plans(core::config::Config& config) {
    // Plans are built whole before the configuration is released, not exchange by exchange:
    // the plans then sit together above the freed configuration, which malloc_trim can give
    // back (interleaving them left the resident memory higher: docs/decisions/0001).
    auto plans = core::config::make_plans(config);
    // Swapped with empty vectors, not assigned `{}`: that keeps the capacity.
    std::vector<core::config::ExchangeConfig>().swap(config.exchanges);
    for (auto& plan : plans) {
        // plan.tags holds every tag spec again: the running exchange reads only that copy.
        // Dropped on every plan, old and new alike, so that reload compares equals.
        std::vector<core::plan::TagSpec>().swap(plan.spec.tags);
    }
    return plans;
}

ReloadSequence::ReloadSequence(boost::asio::any_io_executor loop, ReloadTarget& target,
                               const core::Clock& clock, ReloadWorker::Parse parse_file)
    : loop_(loop),
      target_(target),
      clock_(clock),
      timer_(loop),
      worker_(std::move(parse_file), [this](ParseResult parsed) {
          // Held by a pointer: the handler moves cheaply (and GCC 12 sees no variant to warn on).
          boost::asio::post(loop_,
                            [this, parsed = std::make_shared<ParseResult>(std::move(parsed))] {
                                on_parsed(std::move(*parsed));
                            });
      }) {}

ParseResult ReloadSequence::parse(const std::string& path, std::stop_token stop) {
    auto loaded = adapters::yaml::load_config(path, std::move(stop));
    if (!loaded) return core::fail(loaded.error());
    ParsedConfig parsed{std::move(loaded).value(), {}};
    parsed.plans = take_plans(parsed.config);
    return parsed;
}

void ReloadSequence::request() {
    target_.reloading();
    const auto& file = target_.file();
    switch (worker_.request(file)) {
        case ReloadWorker::Request::started:
            ++pending_;
            requested_at_ = clock_.monotonic();
            spdlog::info("SIGHUP: reloading {}", file);
            break;
        case ReloadWorker::Request::queued:
            spdlog::info(
                "SIGHUP: reloading {} again once the parse under way ends (its result is "
                "dropped)",
                file);
            break;
        case ReloadWorker::Request::merged:
            spdlog::info("SIGHUP: reloading {} once the parse under way ends", file);
            break;
    }
}

void ReloadSequence::on_parsed(ParseResult parsed) {
    // Results come in the order of their requests: this is the last one started's.
    Parsed arrived{std::move(parsed), clock_.monotonic() - requested_at_};
    if (applying_) {
        // The one under way ends first: a change applied over its clears could be undone.
        parsed_.push_back(std::move(arrived));
        return;
    }
    begin(std::move(arrived));
}

void ReloadSequence::begin(Parsed parsed) {
    const auto start = clock_.monotonic();
    applying_ = Applying{start, parsed.parse_took, {}, false, 1, {}};
    applying_->applied = target_.apply(std::move(parsed.result), applying_->outcome);
    if (target_.stopping()) return;
    applying_->longest_slice = clock_.monotonic() - start;
    next_slice();
}

void ReloadSequence::next_slice() {
    if (!target_.changes_pending()) {
        finish();
        return;
    }
    const auto units =
        core::config::slice_units(core::config::reload_slice_units, target_.queue_room());
    if (units == 0) {
        timer_.expires_after(queue_drain_wait);
        timer_.async_wait([this](const boost::system::error_code& error) {
            if (!error) next_slice();
        });
        return;
    }
    const auto start = clock_.monotonic();
    target_.publish_changes(units);
    auto& applying = *applying_;
    ++applying.slices;
    applying.longest_slice = std::max(applying.longest_slice, clock_.monotonic() - start);
    // Behind what the loop has ready: datagrams, timers, /healthz's report.
    boost::asio::post(loop_, [this] { next_slice(); });
}

void ReloadSequence::finish() {
    auto applying = std::move(*applying_);
    applying_.reset();
    // After the plans were built and the old ones freed: the parse's heap goes back. On the
    // worker's thread: malloc_trim walks every arena, 30-50 ms after a plant's reload, and the
    // loop waits for an arena's lock only while it allocates in that one.
    if (applying.applied) worker_.post(detail::release_heap);
    for (const auto& line : applying.outcome) spdlog::info("{}", line);
    spdlog::debug(
        "reload: parsed in {} ms off the loop, applied in {} ms on it, in {} slice(s) of at "
        "most {} ms",
        ms(applying.parse_took), ms(clock_.monotonic() - applying.from), applying.slices,
        ms(applying.longest_slice));
    // Ready once no other reload is under way (one SIGHUP came after this one was parsed).
    if (--pending_ == 0) target_.ready();
    if (parsed_.empty()) return;
    auto next = std::move(parsed_.front());
    parsed_.pop_front();
    begin(std::move(next));
}

}  // namespace eip2mqtt::app::reload
