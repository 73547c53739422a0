// The edge node's births and deaths: NBIRTH and DBIRTH, DDEATH and the NDEATH said on the
// connection, and what brings them. A connection and a reload bring births at once; a host's
// rebirth request and its return online go through request_birth(), which coalesces a flood
// of them (NodeSession). A birth over the largest packet the broker takes is not published:
// the node or the device is then not born.

#include <spdlog/spdlog.h>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

void SparkplugNode::request_birth() {
    if (session_.request_birth()) birth();
}

void SparkplugNode::tick(core::MonoTime now) {
    session_.tick(now);
    if (session_.birth_due()) birth();
    commands_.flush_logs(now, stats_.node_births, session_.host_online());
}

bool SparkplugNode::on_acknowledged(std::uint64_t ack_token) {
    switch (session_.acknowledged(ack_token)) {
        case NodeSession::Acknowledged::not_ours:
            return false;
        case NodeSession::Acknowledged::birth_due:
            birth();
            return true;
        case NodeSession::Acknowledged::ours:
            return true;
    }
    return true;
}

void SparkplugNode::birth() {
    const auto start = session_.begin_birth();
    if (start == NodeSession::BirthStart::refused) return;
    if (start == NodeSession::BirthStart::started_unacknowledged) {
        // NodeSession let it go at the deadline: a host may see this NBIRTH before the NDEATH,
        // and take the node for dead.
        spdlog::warn(
            "Sparkplug: the broker did not acknowledge the NDEATH within {} s; births go on "
            "without it",
            death_acknowledgement_timeout.count());
    }
    for (auto& device : devices_.devices()) device.born = false;
    out_.restart_seq();  // NBIRTH is seq 0; every message after it counts on
    metrics_.fill_birth(payload_, session_.bd_seq(), static_cast<std::uint64_t>(clock_.wall_ms()));
    const auto topic = node_topic("NBIRTH");
    if (!out_.publish(topic, payload_)) {
        birth_refused(topic, node_birth_refused_logged_);
        return;
    }
    node_birth_refused_logged_ = false;
    ++stats_.node_births;
    publish_counters();
    session_.set_born();
    for (auto& device : devices_.devices()) {
        if (device.up) device_birth(device);
    }
}

void SparkplugNode::device_birth(Device& device) {
    DeviceRegistry::fill_birth(device, payload_, clock_.wall_ms());
    if (!out_.publish(device.birth_topic, payload_)) {
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
    if (!out_.publish(device.death_topic, payload_)) data_refused();
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
        topic, out_.last_packet_bytes(), out_.max_packet_bytes(),
        out_.limit_configured() ? " (or sparkplug.max_packet_bytes)" : "",
        node ? "the edge node is not born, and publishes nothing"
             : "the device is not born, and none of its data is published");
}

void SparkplugNode::host_online(bool online) {
    session_.set_host_online(online);
    if (online) {
        request_birth();
        return;
    }
    // The will's NDEATH, said now: the host's applications see the node go.
    if (session_.born()) publish_death();
}

void SparkplugNode::publish_death() {
    auto death = session_.death_message(clock_.wall_ms());
    death.ack_token = session_.death_said();
    out_.publish_unsequenced(std::move(death));
    for (auto& device : devices_.devices()) device.born = false;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
