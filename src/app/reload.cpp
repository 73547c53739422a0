// Building the exchanges, at start and on SIGHUP (docs/operations.md, Reload): a
// valid new configuration is applied without dropping the MQTT session or unchanged exchanges;
// added exchanges start, removed ones stop and their retained topics are cleared, changed ones
// restart; the sections' live keys are applied (core/config/config_keys.hpp has every key's
// rule). An invalid file, or one that changes a key only a restart applies, is refused whole
// and the old configuration keeps running. The file is read and checked on the ReloadWorker's
// thread, so the loop goes on receiving, producing and feeding /healthz while a large file
// parses; the loop only compares and applies (Gateway::apply, asked by the
// reload::ReloadSequence, which has the course of a reload). The exchanges are swapped in one
// handler; what the change publishes (a removed plant's retained topics cleared, new
// descriptions) follows in slices.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <string>
#include <system_error>
#include <utility>

#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/config/reload_plan.hpp"

namespace eip2mqtt::app {
namespace {

using core::config::ReloadRule;

std::vector<adapters::udp::MulticastMembership> memberships(const core::config::EipSection& eip) {
    std::vector<adapters::udp::MulticastMembership> out;
    for (const auto& group : eip.multicast) out.push_back({group.group, group.interface});
    return out;
}

}  // namespace

std::string Gateway::apply_plans(std::vector<core::plan::ExchangePlan> plans) {
    const auto report = exchanges_.apply(std::move(plans), clock_.monotonic(), clock_.wall());
    writes_.count_cancelled(report.cancelled_writes);
    return fmt::format(
        "configuration applied: {} exchange(s) kept, {} started, {} stopped ({}); {} retained "
        "topic(s) cleared",
        report.kept.size(), report.started.size(), report.stopped.size(), report.changes,
        report.cleared_topics);
}

void Gateway::republish_exchanges() {
    json_tree_->republish_meta();  // nothing when the JSON tree is off (sparkplug.uns: false)
    exchanges_.republish(clock_.monotonic(), clock_.wall());
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
    for (auto& module : modules_) module->apply(next);
    return true;
}

bool Gateway::changes_pending() const { return json_tree_->changes_pending(); }

void Gateway::publish_changes(std::size_t units) { json_tree_->publish_changes(units); }

core::config::PublishQueueRoom Gateway::queue_room() const {
    const auto stats = mqtt_->stats();
    return {stats.queued, config_.mqtt.buffer_max_messages, stats.connected};
}

bool Gateway::apply(ParseResult parsed, std::vector<std::string>& outcome) {
    if (!parsed) {
        for (const auto& diagnostic : parsed.error()) spdlog::error("{}", diagnostic.to_string());
        spdlog::error("reload refused: {} has {} error(s); the running configuration is kept",
                      config_.file, parsed.error().size());
        return false;
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
        return false;
    }
    const bool republish =
        northbound::json_tree::json_tree_options(config).publish != json_tree_->options().publish;
    const bool metrics_interval = config.mqtt.metrics_interval != config_.mqtt.metrics_interval;
    if (!apply_settings(config)) return false;
    config_ = std::move(config);
    if (metrics_interval) schedule_metrics();  // the wait under way was for the old interval
    try {
        outcome.push_back(apply_plans(std::move(plans)));
    } catch (const std::exception& e) {
        spdlog::critical("reload failed half-way: {}; exiting for a clean restart", e.what());
        stopping_ = true;
        loop_.stop();
        return false;
    }
    if (republish) republish_exchanges();
    outcome.push_back(changes.empty() ? "reload: no key changed"
                                      : "reload: applied " + changes.describe(ReloadRule::live));
    return true;
}

}  // namespace eip2mqtt::app
