#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <limits>
#include <string>

#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/app/redundancy/role.hpp"
#include "eip2mqtt/core/redundancy/acked_watermarks.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace {

using namespace std::chrono_literals;

// How long a clean stop waits for queued publications before giving up.
constexpr auto stop_flush_timeout = 3s;

/// What only the unit holding the role says: the plant's retained values, `_values`, and a
/// takeover's `_history` replay (its tokens are the role's, core::redundancy::AckedWatermarks).
/// Never the unit's own topics (state, metrics, role) nor the exchanges' `_meta`, which every
/// unit says; store and forward's `_history` goes whoever holds the role: each unit replays
/// what it journaled.
redundancy::Role::MaySend role_topics(const std::string& base_topic) {
    return [gateway = base_topic + "/_gateway/"](const adapters::mqtt::Message& m) {
        const bool role_held = m.historical ? core::redundancy::AckedWatermarks::owns(m.ack_token)
                                            : m.retain || m.batch_lane;
        return role_held && !m.topic.starts_with(gateway) && !m.topic.ends_with("/_meta");
    };
}

adapters::mqtt::ClientOptions client_options(const core::config::Config& config,
                                             std::size_t connection, redundancy::Role& role) {
    const auto& base = core::config::mqtt_connection(config, connection).base_topic;
    auto options =
        mqtt_client_options(config, base + "/_gateway/" + config.gateway.id + "/state", connection);
    options.may_send = role.may_send(role_topics(base));
    return options;
}

/// The publisher of a connection whose base_topic is not the first's; null for the others.
std::unique_ptr<RebasedPublisher> rebased(const core::config::Config& config,
                                          std::size_t connection,
                                          adapters::mqtt::Publisher& client) {
    auto rebase = connection_rebase(config, connection);
    if (rebase.identity()) return nullptr;
    return std::make_unique<RebasedPublisher>(client, std::move(rebase));
}

}  // namespace

JsonTreeModule::JsonTreeModule(const core::config::Config& config, const NorthboundParts& parts,
                               std::size_t connection)
    : clock_(parts.clock),
      exchanges_(parts.exchanges),
      connection_(connection),
      name_(core::config::connection_name(core::config::mqtt_connection(config, connection))),
      buffer_max_messages_(core::config::mqtt_connection(config, connection).buffer_max_messages),
      client_(std::make_unique<adapters::mqtt::Client>(
          parts.loop, client_options(config, connection, parts.role))),
      rebased_(rebased(config, connection, *client_)),
      tree_(json_tree_options(config, connection),
            rebased_ ? static_cast<adapters::mqtt::Publisher&>(*rebased_) : *client_,
            parts.writes) {}

void JsonTreeModule::republish() {
    tree_.republish_meta();
    const auto again = [this] { exchanges_.republish(clock_.monotonic(), clock_.wall()); };
    if (republish_scope_) {
        republish_scope_(again);
    } else {
        again();
    }
}

void JsonTreeModule::start(core::MonoTime /*now*/) {
    client_->set_on_connected([this] { connected(); });
    if (!takers_.empty()) {
        client_->set_on_acknowledged([this](std::uint64_t token) { acknowledged(token); });
    }
    client_->set_on_message([this](const adapters::mqtt::Incoming& message) {
        if (rebased_) return tree_.on_message(rebased_->inward(message));
        tree_.on_message(message);
    });
    client_->start();
}

void JsonTreeModule::connected() {
    spdlog::info("republishing retained state of {} exchange(s)",
                 exchanges_.consumers().size() + exchanges_.producers().size());
    republish();
    // History goes behind the current state.
    for (const auto& listener : connected_) listener(clock_.monotonic());
}

void JsonTreeModule::acknowledged(std::uint64_t token) {
    for (const auto& taker : takers_) {
        if (taker(token)) return;
    }
}

void JsonTreeModule::tick(const TickTimes& /*times*/) { tree_.publish_due_meta(); }

void JsonTreeModule::stop() {
    tree_.publish_changes(std::numeric_limits<std::size_t>::max());
    client_->stop(stop_flush_timeout);
}

void JsonTreeModule::apply(const core::config::Config& next) {
    const auto& mqtt = core::config::mqtt_connection(next, connection_);
    client_->set_buffer_capacity(mqtt.buffer_max_messages);
    client_->set_batch_first(mqtt.batch_first);
    buffer_max_messages_ = mqtt.buffer_max_messages;
    auto options = json_tree_options(next, connection_);
    republish_due_ = options.publish != tree_.options().publish;
    // Response topics and the like take effect at once; tags are published in the new form
    // from their next sample, and their retained state once the reload is applied.
    tree_.set_options(std::move(options));
}

void JsonTreeModule::applied() {
    if (!republish_due_) return;
    republish_due_ = false;
    republish();
}

std::optional<core::config::PublishQueueRoom> JsonTreeModule::queue_room() const {
    const auto stats = client_->stats();
    return core::config::PublishQueueRoom{stats.queued, buffer_max_messages_, stats.connected};
}

void JsonTreeModule::add_metrics(MetricsSources& sources) {
    if (connection_ == 0) {
        sources.mqtt = client_->stats();
        sources.mqtt_name = name_;
    } else {
        sources.more_connections.push_back({name_, client_->stats()});
    }
}

}  // namespace eip2mqtt::app::northbound::json_tree
