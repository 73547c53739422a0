// The edge node's births and deaths: NBIRTH and DBIRTH, DDEATH, and what brings them. A
// connection, a reload and the primary host online bring births at once; a host's rebirth
// request goes through request_birth(), which answers the first at once and coalesces a flood
// (NodeSession). A birth over the largest packet the broker takes is not published: the node
// or the device is then not born. The host offline makes the node leave its broker.

#include <spdlog/spdlog.h>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

void SparkplugNode::request_birth() {
    if (session_.request_birth()) birth(true);
}

void SparkplugNode::tick(core::MonoTime now) {
    session_.tick(now);
    if (session_.birth_due()) birth(true);
    commands_.flush_logs(now, stats_.node_births, session_.host_online());
}

void SparkplugNode::birth(bool requested) {
    if (!session_.begin_birth(requested)) return;
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
    const bool was_born = session_.born();
    session_.set_host_online(online);
    if (online) {
        birth(false);
        return;
    }
    for (auto& device : devices_.devices()) device.born = false;
    // Sparkplug B 3.0: the node ends its session with this broker (its NDEATH, the will, then
    // DISCONNECT) and looks for the host on the next one. A node not born yet waits here.
    if (!was_born) return;
    session_.left();
    leave_broker_();
}

}  // namespace eip2mqtt::app::northbound::sparkplug
