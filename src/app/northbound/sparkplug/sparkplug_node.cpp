// The edge node's façade: the connection and its will, the exchanges' events, commands and
// the node's metrics (NDATA), each handed to the part whose duty it is. Births, deaths and what
// brings them are in sparkplug_births.cpp.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

#include <algorithm>
#include <string_view>

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

constexpr std::string_view namespace_prefix = "spBv1.0/";

}  // namespace

SparkplugOptions sparkplug_options(const core::config::Config& config) {
    const auto& section = config.sparkplug;
    return {section.group_id, core::config::sparkplug_node_id(config), section.primary_host_id,
            section.max_packet_bytes, std::nullopt};
}

SparkplugNode::SparkplugNode(SparkplugOptions options, adapters::mqtt::Publisher& mqtt,
                             WriteHandler& writes, const core::Clock& clock,
                             std::function<void()> leave_broker)
    : options_(std::move(options)),
      clock_(clock),
      session_(node_topic("NDEATH"), !options_.primary_host_id.empty(), options_.last_bd_seq),
      out_(mqtt, clock, options_.max_packet_bytes),
      devices_(options_.group_id, options_.edge_node_id),
      commands_(options_.group_id, options_.edge_node_id, options_.primary_host_id, writes, *this),
      leave_broker_(std::move(leave_broker)) {
    mqtt.set_subscriptions(commands_.subscriptions());
}

std::string SparkplugNode::node_topic(std::string_view type) const {
    return std::string(namespace_prefix) + options_.group_id + "/" + std::string(type) + "/" +
           options_.edge_node_id;
}

adapters::mqtt::Message SparkplugNode::next_will() {
    session_.next_will();
    return session_.death_message(clock_.wall_ms());
}

void SparkplugNode::begin_session(std::optional<std::uint8_t> heard) {
    session_.begin_session(heard);
}

void SparkplugNode::end_session() { session_.end_session(); }

void SparkplugNode::on_connected(std::size_t max_packet_bytes) {
    session_.connected();
    out_.connected(max_packet_bytes);
    commands_.connected();
    birth(false);
}

void SparkplugNode::on_message(const adapters::mqtt::Incoming& message) {
    switch (commands_.on_message(message, devices_, session_)) {
        case NodeCommands::Asked::nothing:
            return;
        case NodeCommands::Asked::rebirth:
            ++stats_.rebirth_requests;
            publish_counters();
            // Answered at once; a flood of them after it makes one rebirth a second.
            request_birth();
            return;
        case NodeCommands::Asked::host_online:
            host_online(true);
            return;
        case NodeCommands::Asked::host_offline:
            host_online(false);
            return;
    }
}

void SparkplugNode::exchanges_changed(const ExchangeSet& running, std::span<const std::string>) {
    // Node metrics are listed in NBIRTH: those of exchanges are rebuilt, then all are born again.
    metrics_.exchanges_changed(running);
    devices_.exchanges_changed(running);
    if (session_.born()) birth(false);
}

void SparkplugNode::tag_samples(const SampleBatch& batch) {
    auto* device = devices_.find(&batch.exchange);
    if (device == nullptr) return;
    if (DeviceRegistry::record(*device, batch)) {
        if (session_.born()) device_birth(*device);
        return;
    }
    // A batch of every tag is the JSON tree's republication after its reconnect: the births
    // hold these values already.
    if (!session_.may_send_data() || !device->born || batch.all_tags ||
        batch.quality != core::quality::Quality::good) {
        return;
    }
    publish_data(*device, batch, false);
}

bool SparkplugNode::replay(const SampleBatch& batch, std::uint64_t ack_token) {
    auto* device = devices_.find(&batch.exchange);
    if (device == nullptr) return false;
    if (!session_.may_send_data() || !device->born ||
        batch.quality != core::quality::Quality::good) {
        return false;
    }
    // Refused for its size, it never will be published: the journal must not wait for it.
    return publish_data(*device, batch, true, ack_token);
}

bool SparkplugNode::publish_data(Device& device, const SampleBatch& batch, bool historical,
                                 std::uint64_t ack_token) {
    DeviceRegistry::fill_data(device, batch, historical, payload_);
    // Nothing changed since it was last reported (a republication of the JSON tree's).
    if (payload_.metrics.empty()) return true;
    if (out_.publish(device.data_topic, payload_, ack_token)) return true;
    data_refused();
    return false;
}

void SparkplugNode::exchange_state(const core::plan::ExchangePlan& exchange,
                                   core::exchange::ConsumeState state) {
    auto* device = devices_.find(&exchange);
    if (device == nullptr || device->produced) return;
    device->up = state == core::exchange::ConsumeState::ok;
    if (!session_.born()) return;
    if (device->up && !device->born) device_birth(*device);
    if (!device->up && device->born) device_death(*device);
}

void SparkplugNode::consumed_status(const ConsumedStatus& status) {
    metrics_.consumed_status(status);
}

void SparkplugNode::produced_status(const core::plan::ExchangePlan& exchange,
                                    const ProducedStatus& status) {
    metrics_.produced_status(exchange, status);
}

void SparkplugNode::gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) {
    metrics_.gateway_metrics(sources, uptime);
    if (!session_.may_send_data()) return;
    metrics_.fill_changes(payload_, static_cast<std::uint64_t>(clock_.wall_ms()));
    if (!payload_.metrics.empty() && !out_.publish(node_topic("NDATA"), payload_)) {
        data_refused();
    }
}

void SparkplugNode::data_refused() {
    ++stats_.data_refused;
    publish_counters();
}

void SparkplugNode::publish_counters() { metrics_.stats(stats_); }

void SparkplugNode::refresh_session() {
    auto& session = stats_.session;
    session.group_id = options_.group_id;
    session.edge_node_id = options_.edge_node_id;
    session.primary_host_id = options_.primary_host_id;
    session.host_online = session_.host_online();
    session.born = session_.born();
    session.bd_seq = session_.session_bd_seq();
    const auto devices = devices_.devices();
    session.devices = devices.size();
    session.devices_born = static_cast<std::size_t>(
        std::count_if(devices.begin(), devices.end(), [](const Device& d) { return d.born; }));
}

void SparkplugNode::widen_node_metrics_for_sizing() { metrics_.widen_for_sizing(); }

}  // namespace eip2mqtt::app::northbound::sparkplug
