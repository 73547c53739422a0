// Building the exchanges, at start and on SIGHUP (README "Running it as a service", Reload; issue
// #4): a valid new configuration is applied without dropping the MQTT session or unchanged
// exchanges; added exchanges start, removed ones stop and their retained topics are cleared,
// changed ones restart. An invalid file is refused with its errors logged, and the old one keeps
// running.

#include <spdlog/spdlog.h>

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_set>

#include "app/detail/release_heap.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"

namespace eip2mqtt::app {
namespace {

/// The settings a reload cannot apply: they shape the MQTT session, the sockets or the
/// identity of the gateway. A change to any of them needs a restart.
auto session_settings(const core::config::Config& c) {
    return std::make_tuple(c.gateway.id, c.gateway.state_dir, c.mqtt.url, c.mqtt.version,
                           c.mqtt.client_id, c.mqtt.username, c.mqtt.password_file,
                           c.mqtt.tls.has_value(), c.mqtt.base_topic, c.mqtt.keepalive,
                           c.mqtt.session_expiry, c.eip.bind, c.eip.port, c.eip.multicast.size(),
                           c.eip.multicast_ttl, c.eip.multicast_interface, c.metrics.listen);
}

/// The retained topics of an exchange: its `_status` and its tags'.
template <class Topics>
void collect_topics(const core::plan::ExchangePlan& plan, Topics& topics) {
    topics.insert(plan.status_topic);
    for (const auto& tag : plan.tags) topics.insert(plan.tag_topic(tag));
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

void Gateway::apply_exchanges(std::vector<core::plan::ExchangePlan> plans, bool running) {
    // Saves still under way must reach the disk before a restarted exchange reads its image.
    if (production_) production_->flush();
    auto sink = [this](adapters::mqtt::Message&& message) { mqtt_->publish(std::move(message)); };
    std::map<std::string, std::unique_ptr<ExchangeConsumer>> old_consumers;
    for (auto& consumer : consumers_) {
        auto name = consumer->plan().spec.name;
        old_consumers.emplace(std::move(name), std::move(consumer));
    }
    std::map<std::string, std::unique_ptr<ExchangeProducer>> old_producers;
    for (auto& producer : producers_) {
        auto name = producer->plan().spec.name;
        old_producers.emplace(std::move(name), std::move(producer));
    }
    consumers_.clear();
    producers_.clear();

    std::vector<ExchangeConsumer*> started_consumers;
    std::vector<ExchangeProducer*> started_producers;
    std::size_t kept = 0;
    for (auto& plan : plans) {
        if (plan.spec.direction == core::plan::Direction::consume) {
            const auto old = old_consumers.find(plan.spec.name);
            if (old != old_consumers.end() && old->second->plan() == plan &&
                old->second->settings() == publish_settings_) {
                consumers_.push_back(std::move(old->second));
                old_consumers.erase(old);
                ++kept;
                continue;
            }
            consumers_.push_back(
                std::make_unique<ExchangeConsumer>(std::move(plan), publish_settings_, sink));
            started_consumers.push_back(consumers_.back().get());
            continue;
        }
        const auto old = old_producers.find(plan.spec.name);
        if (old != old_producers.end() && old->second->plan() == plan &&
            old->second->settings() == publish_settings_) {
            producers_.push_back(std::move(old->second));
            old_producers.erase(old);
            ++kept;
            continue;
        }
        const auto destination =
            adapters::udp::resolve_endpoint(plan.spec.destination, config_.eip.port);
        if (!destination) {
            throw std::runtime_error("exchange " + plan.spec.name +
                                     ": cannot resolve destination " + plan.spec.destination);
        }
        if (!sender_) {
            // Opened with the first produced exchange: a consume-only gateway has one socket.
            adapters::udp::SenderOptions sender_options;
            sender_options.bind = config_.eip.bind;
            sender_options.multicast_ttl = config_.eip.multicast_ttl;
            sender_options.multicast_interface = config_.eip.multicast_interface;
            sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
            production_ =
                std::make_unique<ProducerScheduler>(loop_.get_executor(), *sender_, image_store_);
        }
        producers_.push_back(std::make_unique<ExchangeProducer>(
            std::move(plan), *destination, *production_, image_store_, publish_settings_, sink));
        started_producers.push_back(producers_.back().get());
    }

    // What is left of the old exchanges was removed or changed: stop it, and clear its retained
    // topics that no exchange of the new configuration publishes, so that no subscriber keeps
    // reading a tag that no longer exists. Its queued writes, which it will never produce, are
    // answered now: never silence. (Those its last datagrams carried got their results from
    // the flush above.)
    std::set<std::string> cleared;
    for (auto& [name, producer] : old_producers) {
        producer->stop();
        counters_.writes_cancelled += producer->cancel_queued_writes("reloaded");
        collect_topics(producer->plan(), cleared);
    }
    for (auto& [name, consumer] : old_consumers) collect_topics(consumer->plan(), cleared);
    // The new exchanges' topics, built only when something was removed or changed: a set of
    // every tag topic costs a string per tag (plans do not keep tag topics).
    std::unordered_set<std::string> new_topics;
    if (!cleared.empty()) {
        for (const auto& consumer : consumers_) collect_topics(consumer->plan(), new_topics);
        for (const auto& producer : producers_) collect_topics(producer->plan(), new_topics);
    }
    std::size_t cleared_count = 0;
    for (const auto& topic : cleared) {
        if (new_topics.contains(topic)) continue;
        mqtt_->publish({topic, "", publish_settings_.qos, true, true});
        ++cleared_count;
    }

    by_key_.clear();
    for (auto& consumer : consumers_) by_key_.emplace(consumer->plan().key(), consumer.get());
    build_write_routes();
    if (!running) return;

    mqtt_->set_subscriptions(write_subscriptions());
    const auto now = std::chrono::steady_clock::now();
    const auto wall = std::chrono::system_clock::now();
    for (std::size_t i = 0; i < started_producers.size(); ++i) {
        started_producers[i]->start(now, i, started_producers.size());
        started_producers[i]->republish(wall);
    }
    for (auto* consumer : started_consumers) consumer->republish(now, wall);
    spdlog::info(
        "configuration applied: {} exchange(s) kept, {} started, {} stopped; {} retained "
        "topic(s) cleared",
        kept, started_consumers.size() + started_producers.size(),
        old_consumers.size() + old_producers.size(), cleared_count);
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
            "reload refused: changes to the gateway, mqtt, eip or metrics sections need a restart "
            "(systemctl restart eip2mqtt); the running configuration is kept");
        notifier_.ready(status_line());
        return;
    }
    set_log_level(config.gateway.log_level);
    config_ = std::move(config);
    publish_settings_ = {config_.mqtt.qos, config_.mqtt.retain, config_.mqtt.payload,
                         config_.mqtt.batch};
    mqtt_->set_buffer_capacity(config_.mqtt.buffer_max_messages);
    try {
        apply_exchanges(take_plans(), true);
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
