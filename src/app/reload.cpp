// Building the exchanges, at start and on SIGHUP (README "Running it as a service", Reload): a
// valid new configuration is applied without dropping the MQTT session or unchanged exchanges;
// added exchanges start, removed ones stop and their retained topics are cleared, changed ones
// restart; the sections' live keys are applied (core/config/config_keys.hpp has every key's
// rule). An invalid file, or one that changes a key only a restart applies, is refused whole
// and the old configuration keeps running.

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <string>
#include <system_error>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/config/reload_plan.hpp"
#include "eip2mqtt/core/plan/plan_diff.hpp"

namespace eip2mqtt::app {
namespace {

using core::config::ReloadRule;

std::vector<adapters::udp::MulticastMembership> memberships(const core::config::EipSection& eip) {
    std::vector<adapters::udp::MulticastMembership> out;
    for (const auto& group : eip.multicast) out.push_back({group.group, group.interface});
    return out;
}

/// The image of the producer that `plan` replaces, when a reload changes its exchange but not
/// the layout of its image: the running image goes on, whatever its file holds.
std::optional<ImageHandover> handover_for(
    const core::plan::ExchangePlan& plan,
    const std::vector<std::unique_ptr<ExchangeProducer>>& old_producers) {
    for (const auto& producer : old_producers) {
        if (!producer || producer->plan().spec.name != plan.spec.name) continue;
        if (adapters::state::layout_fingerprint(producer->plan()) !=
            adapters::state::layout_fingerprint(plan)) {
            return std::nullopt;
        }
        return producer->hand_over();
    }
    return std::nullopt;
}

}  // namespace

std::vector<core::plan::ExchangePlan> Gateway::take_plans(core::config::Config& config) {
    // Plans are built whole before the configuration is released, not exchange by exchange:
    // the plans then sit together above the freed configuration, which malloc_trim can give
    // back (interleaving them left RSS 16 MB higher for 100,000 tags).
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

core::plan::PlanDiff Gateway::diff_running(
    const std::vector<core::plan::ExchangePlan>& plans) const {
    return core::plan::diff_plans(running_plans(), plans);
}

std::vector<const core::plan::ExchangePlan*> Gateway::running_plans() const {
    auto running = running_exchanges();
    auto& plans = running.consumed;
    plans.insert(plans.end(), running.produced.begin(), running.produced.end());
    return plans;
}

ExchangeSet Gateway::running_exchanges() const {
    ExchangeSet running;
    running.consumed.reserve(consumers_.size());
    for (const auto& consumer : consumers_) running.consumed.push_back(&consumer->plan());
    running.produced.reserve(producers_.size());
    for (const auto& producer : producers_) running.produced.push_back(&producer->plan());
    return running;
}

std::unique_ptr<ExchangeProducer> Gateway::make_producer(core::plan::ExchangePlan plan,
                                                         std::optional<ImageHandover> handover) {
    const auto destination =
        adapters::udp::resolve_endpoint(plan.spec.destination, config_.eip.port);
    if (!destination) {
        throw std::runtime_error("exchange " + plan.spec.name + ": cannot resolve destination " +
                                 plan.spec.destination);
    }
    if (!sender_) {
        // Opened with the first produced exchange: a consume-only gateway has one socket.
        adapters::udp::SenderOptions sender_options;
        sender_options.bind = config_.eip.bind;
        sender_options.multicast_ttl = config_.eip.multicast_ttl;
        sender_options.multicast_interface = config_.eip.multicast_interface;
        sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
        production_ = std::make_unique<ProducerScheduler>(loop_.get_executor(), *sender_);
        persister_ =
            std::make_unique<adapters::state::ImagePersister>(image_store_, loop_.get_executor());
    }
    return std::make_unique<ExchangeProducer>(std::move(plan), *destination, *production_,
                                              *persister_, northbound_, writes_.image_saves(),
                                              std::move(handover));
}

void Gateway::apply_exchanges(std::vector<core::plan::ExchangePlan> plans, bool running) {
    // Saves still under way must reach the disk, and their writes their results, before an
    // image is handed over or read.
    if (persister_) persister_->flush();

    const auto diff = diff_running(plans);
    // Named for the log before the plans move into the exchanges.
    const auto changes =
        running ? core::plan::describe_diff(diff, running_plans(), plans) : std::string();

    auto old_consumers = std::move(consumers_);
    auto old_producers = std::move(producers_);
    consumers_.clear();
    producers_.clear();
    const auto old_consumer_count = old_consumers.size();

    std::vector<ExchangeConsumer*> started_consumers;
    std::vector<ExchangeProducer*> started_producers;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < plans.size(); ++i) {
        auto& plan = plans[i];
        if (const auto from = diff.kept_from[i]) {
            if (*from < old_consumer_count) {
                consumers_.push_back(std::move(old_consumers[*from]));
            } else {
                producers_.push_back(std::move(old_producers[*from - old_consumer_count]));
            }
            ++kept;
            continue;
        }
        if (plan.spec.direction == core::plan::Direction::consume) {
            consumers_.push_back(std::make_unique<ExchangeConsumer>(std::move(plan), northbound_));
            started_consumers.push_back(consumers_.back().get());
            continue;
        }
        auto handover = handover_for(plan, old_producers);
        producers_.push_back(make_producer(std::move(plan), std::move(handover)));
        started_producers.push_back(producers_.back().get());
    }

    // A stopped producer's queued writes, which it will never produce, are answered now: never
    // silence. (Those its last datagrams carried got their results from the flush above.)
    // Stopped consumers need nothing: they go with old_consumers.
    for (const auto index : diff.stopped) {
        if (index < old_consumer_count) continue;
        auto& producer = old_producers[index - old_consumer_count];
        producer->stop();
        writes_.count_cancelled(producer->cancel_queued_writes("reloaded"));
    }
    // The northbounds forget retired exchanges (retained topics cleared) and learn the new ones
    // (the JSON tree's `set` subscriptions).
    northbound_.exchanges_changed(running_exchanges(), diff.cleared);
    datagram_router_.set_consumers(consumers_);
    for (std::size_t i = 0; i < started_consumers.size(); ++i) {
        started_consumers[i]->set_status_phase(i, started_consumers.size());
    }
    if (!running) return;

    const auto now = std::chrono::steady_clock::now();
    const auto wall = std::chrono::system_clock::now();
    for (std::size_t i = 0; i < started_producers.size(); ++i) {
        started_producers[i]->start(now, i, started_producers.size());
        started_producers[i]->republish(wall);
    }
    for (auto* consumer : started_consumers) consumer->republish(now);
    spdlog::info(
        "configuration applied: {} exchange(s) kept, {} started, {} stopped ({}); {} retained "
        "topic(s) cleared",
        kept, started_consumers.size() + started_producers.size(), diff.stopped.size(), changes,
        diff.cleared.size());
}

void Gateway::republish_exchanges() {
    const auto now = std::chrono::steady_clock::now();
    const auto wall = std::chrono::system_clock::now();
    uns_json_->republish_meta();  // nothing when the JSON tree is off (sparkplug.uns: false)
    for (auto& consumer : consumers_) consumer->republish(now);
    for (auto& producer : producers_) producer->republish(wall);
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
    uns_json_->set_options(northbound::uns_json_options(next));
    if (commands_) commands_->set_policy(command_policy(next));
    return true;
}

void Gateway::reload() {
    notifier_.reloading();
    spdlog::info("SIGHUP: reloading {}", config_.file);
    auto loaded = adapters::yaml::load_config(config_.file);
    if (!loaded) {
        for (const auto& diagnostic : loaded.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::error("reload refused: {} has {} error(s); the running configuration is kept",
                      config_.file, loaded.error().size());
        notifier_.ready(status_line());
        return;
    }
    auto config = std::move(loaded).value();
    auto plans = take_plans(config);
    const auto changes = core::config::plan_reload(config_, running_plans(), config, plans);
    if (changes.needs_restart) {
        const auto restart = changes.describe(ReloadRule::restart);
        const auto live = changes.describe(ReloadRule::live);
        spdlog::error(
            "reload refused: {} {} a restart (systemctl restart eip2mqtt); nothing is applied{}; "
            "the running configuration is kept",
            restart, restart.find(", ") == std::string::npos ? "needs" : "need",
            live.empty() ? "" : " (also changed: " + live + ")");
        notifier_.ready(status_line());
        return;
    }
    const bool republish =
        northbound::uns_json_options(config).publish != uns_json_->options().publish;
    const bool metrics_interval = config.mqtt.metrics_interval != config_.mqtt.metrics_interval;
    if (!apply_settings(config)) {
        notifier_.ready(status_line());
        return;
    }
    config_ = std::move(config);
    if (metrics_interval) schedule_metrics();  // the wait under way was for the old interval
    try {
        apply_exchanges(std::move(plans), true);
    } catch (const std::exception& e) {
        spdlog::critical("reload failed half-way: {}; exiting for a clean restart", e.what());
        stopping_ = true;
        loop_.stop();
        return;
    }
    if (republish) republish_exchanges();
    if (changes.empty()) {
        spdlog::info("reload: no key changed");
    } else {
        spdlog::info("reload: applied {}", changes.describe(ReloadRule::live));
    }
    detail::release_heap();
    notifier_.ready(status_line());
}

}  // namespace eip2mqtt::app
