// The edge node's births: NBIRTH and DBIRTH, and what brings them. A connection and a reload
// bring them at once; a host's rebirth request and its return online go through
// request_birth(), which coalesces a flood of them. A birth over the largest packet the broker
// takes is not published: the node or the device is then not born.

#include <spdlog/spdlog.h>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using adapters::sparkplug::DataType;
using adapters::sparkplug::Metric;
using core::plan::Value;

/// Node metric 0, in every NBIRTH (Sparkplug B 3.0 requires it).
constexpr std::size_t bd_seq_metric = 0;
/// How long births wait for the broker's acknowledgement of the NDEATH before them: a broker
/// that never answers it must not keep the node from being born for good.
constexpr std::chrono::seconds death_acknowledgement_timeout{10};

}  // namespace

void SparkplugNode::request_birth() {
    if (birth_may_start()) {
        birth();
    } else {
        rebirth_pending_ = true;
    }
}

bool SparkplugNode::birth_may_start() const {
    // A host takes an NDEATH carrying the current NBIRTH's bdSeq for the node's death, and on
    // one connection every NBIRTH has the same bdSeq: an NDEATH overtaken by the next NBIRTH
    // would leave the node dead. The NDEATH is QoS 1 and births may be QoS 0, which MQTT does
    // not keep in order with it: births wait for its PUBACK.
    const bool death_settled = death_unacknowledged_ == 0 || now_ >= death_deadline_;
    return may_publish() && death_settled && now_ >= birth_hold_until_;
}

void SparkplugNode::tick(core::MonoTime now) {
    now_ = now;
    if (rebirth_pending_ && birth_may_start()) birth();
    if (const auto count = rebirth_log_.flush(now)) {
        spdlog::info("Sparkplug: {} more rebirth requests by NCMD, coalesced ({} NBIRTHs in all)",
                     count, stats_.node_births);
    }
    if (const auto count = state_log_.flush(now)) {
        spdlog::info("Sparkplug primary host {}: {} more STATE changes, now {}",
                     options_.primary_host_id, count, host_online_ ? "online" : "offline");
    }
    if (const auto count = refused_log_.flush(now)) {
        spdlog::warn("Sparkplug: {} more DCMDs refused while the edge node is not born", count);
    }
}

bool SparkplugNode::on_acknowledged(std::uint64_t ack_token) {
    if ((ack_token & sparkplug_own_token) == 0) return false;
    if (ack_token != death_unacknowledged_) return true;  // an NDEATH of an earlier connection
    death_unacknowledged_ = 0;
    if (rebirth_pending_ && birth_may_start()) birth();
    return true;
}

void SparkplugNode::birth() {
    rebirth_pending_ = false;
    if (!may_publish()) return;
    if (death_unacknowledged_ != 0) {
        // birth_may_start() let it go at the deadline: a host may see this NBIRTH before the
        // NDEATH, and take the node for dead.
        spdlog::warn(
            "Sparkplug: the broker did not acknowledge the NDEATH within {} s; births go on "
            "without it",
            death_acknowledgement_timeout.count());
        death_unacknowledged_ = 0;
    }
    // In progress from now: another request waits for the hold to end.
    birth_hold_until_ = now_ + rebirth_hold;
    born_ = false;
    for (auto& device : devices_) device.born = false;
    seq_ = 0;  // NBIRTH is seq 0; every message after it counts on
    set_node_metric(bd_seq_metric, Value{std::int64_t{bd_seq_}});
    const auto now = static_cast<std::uint64_t>(clock_.wall_ms());
    payload_.metrics.clear();
    for (std::size_t i = 0; i < node_metrics_.size(); ++i) {
        auto& metric = node_metrics_[i];
        payload_.metrics.push_back({metric.name, i, now, metric.type, metric.value, false, {}});
        metric.changed = false;
    }
    const auto topic = node_topic("NBIRTH");
    if (!publish(topic, payload_)) {
        birth_refused(topic, node_birth_refused_logged_);
        return;
    }
    node_birth_refused_logged_ = false;
    ++stats_.node_births;
    publish_counters();
    born_ = true;
    for (auto& device : devices_) {
        if (device.up) device_birth(device);
    }
}

void SparkplugNode::device_birth(Device& device) {
    const auto& plan = *device.plan;
    const auto now = clock_.wall_ms();
    payload_.metrics.clear();
    payload_.metrics.reserve(plan.tags.size());
    for (std::size_t i = 0; i < plan.tags.size(); ++i) {
        const auto& spec = plan.tags[i].spec;
        Metric metric{spec.name,
                      device.alias_base + i,
                      static_cast<std::uint64_t>(device.values[i] ? device.timestamps[i] : now),
                      adapters::sparkplug::datatype_of(spec.type),
                      std::nullopt,
                      false,
                      {}};
        if (device.values[i]) metric.value = *device.values[i];
        // Ignition's names where Ignition has one (engUnit, Documentation).
        if (!spec.unit().empty()) {
            metric.properties.push_back({"engUnit", DataType::string, spec.unit()});
        }
        if (!spec.description().empty()) {
            metric.properties.push_back({"Documentation", DataType::string, spec.description()});
        }
        if (device.produced) {
            metric.properties.push_back({"writable", DataType::boolean, Value{spec.writable}});
            if (spec.min())
                metric.properties.push_back({"min", DataType::float64, Value{*spec.min()}});
            if (spec.max())
                metric.properties.push_back({"max", DataType::float64, Value{*spec.max()}});
        }
        payload_.metrics.push_back(std::move(metric));
    }
    if (!publish(device.birth_topic, payload_)) {
        // Not born: no DDATA of it, whose aliases a host could not resolve; tried again with
        // the next rebirth.
        birth_refused(device.birth_topic, device.birth_refused_logged);
        return;
    }
    device.born = true;
    device.birth_refused_logged = false;
}

void SparkplugNode::device_death(Device& device) {
    payload_.metrics.clear();
    if (!publish(device.death_topic, payload_)) data_refused();
    device.born = false;
}

void SparkplugNode::birth_refused(const std::string& topic, bool& logged) {
    ++stats_.births_refused;
    publish_counters();
    if (logged) return;
    logged = true;
    const bool node = topic.find("/NBIRTH/") != std::string::npos;
    spdlog::error(
        "Sparkplug {} not published: {} bytes, over the {} bytes the broker takes{}; {} (said "
        "once; counted in births_refused)",
        topic, last_packet_bytes_, max_packet_bytes_,
        options_.max_packet_bytes != 0 ? " (or sparkplug.max_packet_bytes)" : "",
        node ? "the edge node is not born, and publishes nothing"
             : "the device is not born, and none of its data is published");
}

void SparkplugNode::publish_death() {
    auto death = death_message();
    death.ack_token = sparkplug_own_token | ++next_ack_token_;
    death_unacknowledged_ = death.ack_token;
    death_deadline_ = now_ + death_acknowledgement_timeout;
    mqtt_.publish(std::move(death));
    born_ = false;
    for (auto& device : devices_) device.born = false;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
