// Building the exchanges, at start and on SIGHUP (README "Running it as a service", Reload; issue
// #4): a valid new configuration is applied without dropping the MQTT session or unchanged
// exchanges; added exchanges start, removed ones stop and their retained topics are cleared,
// changed ones restart. An invalid file is refused with its errors logged, and the old one keeps
// running.

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <string>
#include <tuple>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/plan/plan_diff.hpp"

namespace eip2mqtt::app {
namespace {

/// The settings a reload cannot apply: they shape the MQTT session, the sockets or the
/// identity of the gateway. A change to any of them needs a restart.
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

auto session_settings(const core::config::Config& c) {
    return std::make_tuple(
        c.gateway.id, c.gateway.state_dir, c.mqtt.url, c.mqtt.version, c.mqtt.client_id,
        c.mqtt.username, c.mqtt.password_file, c.mqtt.tls.has_value(), c.mqtt.base_topic,
        c.mqtt.keepalive, c.mqtt.session_expiry, c.eip.bind, c.eip.port, c.eip.multicast.size(),
        c.eip.multicast_ttl, c.eip.multicast_interface, c.metrics.listen, c.sparkplug.group_id,
        c.sparkplug.edge_node_id, c.sparkplug.primary_host_id, c.sparkplug.uns, c.sparkplug.qos,
        c.mqtt.store_and_forward);
}

}  // namespace

std::vector<core::plan::ExchangePlan> Gateway::take_plans() {
    // Plans are built whole before the configuration is released, not exchange by exchange:
    // the plans then sit together above the freed configuration, which malloc_trim can give
    // back (interleaving them left RSS 16 MB higher for 100,000 tags).
    auto plans = core::config::make_plans(config_);
    // Swapped with empty vectors, not assigned `{}`: that keeps the capacity.
    std::vector<core::config::ExchangeConfig>().swap(config_.exchanges);
    for (auto& plan : plans) {
        // plan.tags holds every tag spec again: the running exchange reads only that copy.
        // Dropped on every plan, old and new alike, so that reload compares equals.
        std::vector<core::plan::TagSpec>().swap(plan.spec.tags);
    }
    return plans;
}

core::plan::PlanDiff Gateway::diff_running(const std::vector<core::plan::ExchangePlan>& plans,
                                           bool settings_changed) const {
    // The running exchanges, consumers first: diff_plans' indices count in that order.
    auto running = running_exchanges();
    auto& running_plans = running.consumed;
    running_plans.insert(running_plans.end(), running.produced.begin(), running.produced.end());
    return core::plan::diff_plans(running_plans, plans, settings_changed);
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

void Gateway::apply_exchanges(std::vector<core::plan::ExchangePlan> plans, bool running,
                              bool settings_changed) {
    // Saves still under way must reach the disk, and their writes their results, before an
    // image is handed over or read.
    if (persister_) persister_->flush();

    const auto diff = diff_running(plans, settings_changed);

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
        "configuration applied: {} exchange(s) kept, {} started, {} stopped; {} retained "
        "topic(s) cleared",
        kept, started_consumers.size() + started_producers.size(), diff.stopped.size(),
        diff.cleared.size());
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
    if (session_settings(config) != session_settings(config_)) {
        spdlog::error(
            "reload refused: changes to the gateway, mqtt, eip, metrics or sparkplug sections need "
            "a restart (systemctl restart eip2mqtt); the running configuration is kept");
        notifier_.ready(status_line());
        return;
    }
    set_log_level(config.gateway.log_level);
    config_ = std::move(config);
    auto uns_options = northbound::uns_json_options(config_);
    const bool settings_changed = uns_options.publish != uns_json_->options().publish;
    uns_json_->set_options(std::move(uns_options));
    mqtt_->set_buffer_capacity(config_.mqtt.buffer_max_messages);
    try {
        apply_exchanges(take_plans(), true, settings_changed);
    } catch (const std::exception& e) {
        spdlog::critical("reload failed half-way: {}; exiting for a clean restart", e.what());
        stopping_ = true;
        loop_.stop();
        return;
    }
    detail::release_heap();
    notifier_.ready(status_line());
}

}  // namespace eip2mqtt::app
