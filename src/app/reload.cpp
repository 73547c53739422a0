// Building the exchanges, at start and on SIGHUP (docs/operations.md, Reload): a
// valid new configuration is applied without dropping the MQTT session or unchanged exchanges;
// added exchanges start, removed ones stop and their retained topics are cleared, changed ones
// restart; the sections' live keys are applied (core/config/config_keys.hpp has every key's
// rule). An invalid file, or one that changes a key only a restart applies, is refused whole
// and the old configuration keeps running. The file is read and checked on the ReloadWorker's
// thread (parse_reload), so the loop goes on receiving, producing and feeding /healthz while a
// large file parses; the loop only compares and applies (on_reload_parsed). The exchanges are
// swapped in one handler; what the change publishes (a removed plant's retained topics cleared,
// new descriptions) follows in slices of core::config::slice_units, the loop receiving and
// producing between two, and a result that arrives meanwhile waits for the end
// (continue_reload, end_reload).

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/post.hpp>
#include <chrono>
#include <exception>
#include <string>
#include <system_error>
#include <utility>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/config/reload_plan.hpp"
#include "eip2mqtt/core/config/reload_slice.hpp"

namespace eip2mqtt::app {
namespace {

using core::config::ReloadRule;
using namespace std::chrono_literals;

// How long a reload waits for the publish queue to drain before its next slice: a tick.
constexpr auto queue_drain_wait = 10ms;

std::vector<adapters::udp::MulticastMembership> memberships(const core::config::EipSection& eip) {
    std::vector<adapters::udp::MulticastMembership> out;
    for (const auto& group : eip.multicast) out.push_back({group.group, group.interface});
    return out;
}

}  // namespace

std::vector<core::plan::ExchangePlan> Gateway::take_plans(core::config::Config& config) {
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

std::string Gateway::apply_plans(std::vector<core::plan::ExchangePlan> plans) {
    const auto report = exchanges_.apply(std::move(plans), std::chrono::steady_clock::now(),
                                         std::chrono::system_clock::now());
    writes_.count_cancelled(report.cancelled_writes);
    return fmt::format(
        "configuration applied: {} exchange(s) kept, {} started, {} stopped ({}); {} retained "
        "topic(s) cleared",
        report.kept.size(), report.started.size(), report.stopped.size(), report.changes,
        report.cleared_topics);
}

void Gateway::republish_exchanges() {
    json_tree_->republish_meta();  // nothing when the JSON tree is off (sparkplug.uns: false)
    exchanges_.republish(std::chrono::steady_clock::now(), std::chrono::system_clock::now());
}

bool Gateway::apply_settings(const core::config::Config& next) {
    if (next.eip.multicast != config_.eip.multicast) {
        try {
            receiver_->set_multicast(memberships(next.eip));
        } catch (const std::system_error& e) {
            spdlog::error("reload refused: eip.multicast: {}; the running configuration is kept",
                          e.what());
            return false;
        }
    }
    set_log_level(next.gateway.log_level);
    for (auto* client : {mqtt_.get(), sparkplug_mqtt_.get()}) {
        if (client == nullptr) continue;
        client->set_buffer_capacity(next.mqtt.buffer_max_messages);
        client->set_batch_first(next.mqtt.batch_first);
    }
    // Response topics and the like take effect at once; tags are published in the new form
    // from their next sample, and their retained state is published again (reload()).
    json_tree_->set_options(northbound::json_tree::json_tree_options(next));
    if (commands_) commands_->set_policy(command_policy(next));
    return true;
}

ParseResult Gateway::parse_reload(const std::string& path, std::stop_token stop) {
    auto loaded = adapters::yaml::load_config(path, std::move(stop));
    if (!loaded) return core::fail(loaded.error());
    ParsedConfig parsed{std::move(loaded).value(), {}};
    parsed.plans = take_plans(parsed.config);
    return parsed;
}

void Gateway::reload() {
    notifier_.reloading();
    switch (reloads_.request(config_.file)) {
        case ReloadWorker::Request::started:
            ++reloads_pending_;
            reload_requested_at_ = std::chrono::steady_clock::now();
            spdlog::info("SIGHUP: reloading {}", config_.file);
            break;
        case ReloadWorker::Request::queued:
            spdlog::info(
                "SIGHUP: reloading {} again once the parse under way ends (its result is "
                "dropped)",
                config_.file);
            break;
        case ReloadWorker::Request::merged:
            spdlog::info("SIGHUP: reloading {} once the parse under way ends", config_.file);
            break;
    }
}

void Gateway::on_reload_parsed(ParseResult parsed) {
    // Results come in the order of their requests: this is the last one started's.
    ParsedReload arrived{std::move(parsed),
                         std::chrono::steady_clock::now() - reload_requested_at_};
    if (reload_apply_) {
        // The one under way ends first: a change applied over its clears could be undone.
        reloads_parsed_.push_back(std::move(arrived));
        return;
    }
    start_reload(std::move(arrived));
}

void Gateway::start_reload(ParsedReload parsed) {
    const auto start = std::chrono::steady_clock::now();
    reload_apply_ = ReloadApply{start, parsed.parse_took, {}, false, 1, {}};
    apply_reload(std::move(parsed.result));
    if (stopping_) return;
    reload_apply_->longest_slice = std::chrono::steady_clock::now() - start;
    continue_reload();
}

void Gateway::continue_reload() {
    if (!json_tree_->changes_pending()) {
        end_reload();
        return;
    }
    const auto stats = mqtt_->stats();
    const auto units = core::config::slice_units(
        core::config::reload_slice_units,
        {stats.queued, config_.mqtt.buffer_max_messages, stats.connected});
    if (units == 0) {
        reload_timer_.expires_after(queue_drain_wait);
        reload_timer_.async_wait([this](const boost::system::error_code& error) {
            if (!error) continue_reload();
        });
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    json_tree_->publish_changes(units);
    auto& apply = *reload_apply_;
    ++apply.slices;
    apply.longest_slice = std::max(apply.longest_slice, std::chrono::steady_clock::now() - start);
    // Behind what the loop has ready: datagrams, timers, /healthz's report.
    boost::asio::post(loop_, [this] { continue_reload(); });
}

void Gateway::end_reload() {
    auto apply = std::move(*reload_apply_);
    reload_apply_.reset();
    // After the plans were built and the old ones freed: the parse's heap goes back. On the
    // worker's thread: malloc_trim walks every arena, 30-50 ms after a plant's reload, and the
    // loop waits for an arena's lock only while it allocates in that one.
    if (apply.applied) reloads_.post(detail::release_heap);
    for (const auto& line : apply.outcome) spdlog::info("{}", line);
    const auto ms = [](std::chrono::steady_clock::duration d) {
        return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
    };
    const auto now = std::chrono::steady_clock::now();
    spdlog::debug(
        "reload: parsed in {} ms off the loop, applied in {} ms on it, in {} slice(s) of at "
        "most {} ms",
        ms(apply.parse_took), ms(now - apply.applying_from), apply.slices, ms(apply.longest_slice));
    // Ready once no other reload is under way (one SIGHUP came after this one was parsed).
    if (--reloads_pending_ == 0) notifier_.ready(status_line());
    if (reloads_parsed_.empty()) return;
    auto next = std::move(reloads_parsed_.front());
    reloads_parsed_.pop_front();
    start_reload(std::move(next));
}

void Gateway::apply_reload(ParseResult parsed) {
    if (!parsed) {
        for (const auto& diagnostic : parsed.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::error("reload refused: {} has {} error(s); the running configuration is kept",
                      config_.file, parsed.error().size());
        return;
    }
    auto config = std::move(parsed.value().config);
    auto plans = std::move(parsed.value().plans);
    const auto changes =
        core::config::plan_reload(config_, exchanges_.running_plans(), config, plans);
    if (changes.needs_restart) {
        const auto restart = changes.describe(ReloadRule::restart);
        const auto live = changes.describe(ReloadRule::live);
        spdlog::error(
            "reload refused: {} {} a restart (systemctl restart eip2mqtt); nothing is applied{}; "
            "the running configuration is kept",
            restart, restart.find(", ") == std::string::npos ? "needs" : "need",
            live.empty() ? "" : " (also changed: " + live + ")");
        return;
    }
    const bool republish =
        northbound::json_tree::json_tree_options(config).publish != json_tree_->options().publish;
    const bool metrics_interval = config.mqtt.metrics_interval != config_.mqtt.metrics_interval;
    if (!apply_settings(config)) return;
    config_ = std::move(config);
    if (metrics_interval) schedule_metrics();  // the wait under way was for the old interval
    auto& outcome = reload_apply_->outcome;
    try {
        outcome.push_back(apply_plans(std::move(plans)));
        reload_apply_->applied = true;
    } catch (const std::exception& e) {
        spdlog::critical("reload failed half-way: {}; exiting for a clean restart", e.what());
        stopping_ = true;
        loop_.stop();
        return;
    }
    if (republish) republish_exchanges();
    outcome.push_back(changes.empty() ? "reload: no key changed"
                                      : "reload: applied " + changes.describe(ReloadRule::live));
}

}  // namespace eip2mqtt::app
