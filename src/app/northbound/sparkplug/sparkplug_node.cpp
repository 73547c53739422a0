// The edge node's lifecycle and data: the connection and its will, devices, DDATA by exception
// and the node's metrics (NDATA). Births are in sparkplug_births.cpp, commands and the primary
// host's STATE in sparkplug_commands.cpp.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <string_view>

#include "eip2mqtt/app/health/gateway_metrics.hpp"
#include "eip2mqtt/core/redundancy/bd_seq.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using adapters::sparkplug::DataType;
using adapters::sparkplug::MetricValue;
using core::plan::Value;

constexpr std::string_view namespace_prefix = "spBv1.0/";
/// Node metric 1, in every NBIRTH (Sparkplug B 3.0 requires it, after bdSeq).
constexpr std::size_t rebirth_metric = 1;
constexpr std::array<const char*, 4> gateway_counters{"Gateway/uptime_s", "Gateway/datagrams",
                                                      "Gateway/accepted", "Gateway/dropped"};
constexpr std::array<const char*, 4> node_counters{
    "Sparkplug/births_refused", "Sparkplug/data_refused", "Sparkplug/rebirth_requests",
    "Sparkplug/node_births"};

constexpr std::size_t write_metric_count() {
    std::size_t count = 0;
    for (const auto& field : core::write::write_counter_fields) {
        if (field.in(core::in_sparkplug)) ++count;
    }
    return count;
}

/// bdSeq, Rebirth, the gateway's counters, those of its writes and the node's (SparkplugStats);
/// each exchange's metrics follow.
constexpr std::size_t fixed_node_metrics =
    2 + gateway_counters.size() + write_metric_count() + node_counters.size();

std::string write_metric_name(const core::write::WriteCounterField& field) {
    return "Gateway/" + std::string(field.name);
}

std::uint64_t sum(std::span<const std::uint64_t> values) {
    std::uint64_t total = 0;
    for (const auto v : values) total += v;
    return total;
}

Value counter(std::uint64_t value) { return Value{value}; }

}  // namespace

SparkplugOptions sparkplug_options(const core::config::Config& config) {
    const auto& section = config.sparkplug;
    return {section.group_id, core::config::sparkplug_node_id(config), section.primary_host_id,
            section.qos, section.max_packet_bytes};
}

SparkplugNode::SparkplugNode(SparkplugOptions options, adapters::mqtt::Publisher& mqtt,
                             WriteHandler& writes, const core::Clock& clock)
    : options_(std::move(options)), mqtt_(mqtt), writes_(writes), clock_(clock) {
    ncmd_topic_ = node_topic("NCMD");
    dcmd_prefix_ =
        std::string(namespace_prefix) + options_.group_id + "/DCMD/" + options_.edge_node_id + "/";
    std::vector<std::string> filters{ncmd_topic_, dcmd_prefix_ + "+"};
    if (!options_.primary_host_id.empty()) {
        state_topic_ = std::string(namespace_prefix) + "STATE/" + options_.primary_host_id;
        filters.push_back(state_topic_);
    }
    mqtt_.set_subscriptions(std::move(filters));
    node_metric("bdSeq", DataType::int64);
    node_metric("Node Control/Rebirth", DataType::boolean);
    set_node_metric(rebirth_metric, Value{false});
    for (const auto* name : gateway_counters) {
        set_node_metric(node_metric(name, DataType::uint64), counter(0));
    }
    for (const auto& field : core::write::write_counter_fields) {
        if (!field.in(core::in_sparkplug)) continue;
        set_node_metric(node_metric(write_metric_name(field), DataType::uint64), counter(0));
    }
    for (const auto* name : node_counters) {
        set_node_metric(node_metric(name, DataType::uint64), counter(0));
    }
}

std::string SparkplugNode::node_topic(std::string_view type) const {
    return std::string(namespace_prefix) + options_.group_id + "/" + std::string(type) + "/" +
           options_.edge_node_id;
}

adapters::mqtt::Message SparkplugNode::next_will() {
    // A CONNECT that made no connection registered no will a host could have seen: its bdSeq
    // goes with the next attempt, so that an outage does not move it by one per attempt.
    if (will_connected_) {
        bd_seq_ = next_bd_seq_++;  // 255 is followed by 0
        will_connected_ = false;
    }
    session_open_ = true;
    return death_message();
}

void SparkplugNode::begin_session(std::optional<std::uint8_t> heard) {
    next_bd_seq_ = core::redundancy::next_session_bd_seq(heard, next_bd_seq_);
    will_connected_ = true;  // taken by the next will, whatever became of the last CONNECT
}

void SparkplugNode::end_session() {
    connected_ = false;
    born_ = false;
    session_open_ = false;
    host_online_ = false;
    rebirth_pending_ = false;
    death_unacknowledged_ = 0;
}

adapters::mqtt::Message SparkplugNode::death_message() const {
    adapters::sparkplug::Payload death;
    death.timestamp_ms = static_cast<std::uint64_t>(clock_.wall_ms());
    death.metrics.push_back({"bdSeq",
                             std::nullopt,
                             death.timestamp_ms,
                             DataType::int64,
                             Value{std::int64_t{bd_seq_}},
                             false,
                             {}});
    adapters::mqtt::Message message;
    message.topic = node_topic("NDEATH");
    message.payload = adapters::sparkplug::encode(death);
    message.qos = 1;  // the specification's: a host must learn of the death
    message.retain = false;
    message.coalesce = false;
    return message;
}

void SparkplugNode::on_connected(std::size_t max_packet_bytes) {
    connected_ = true;
    will_connected_ = true;
    born_ = false;
    max_packet_bytes_ = options_.max_packet_bytes == 0
                            ? max_packet_bytes
                            : std::min(max_packet_bytes, options_.max_packet_bytes);
    // What waited on the last connection is moot: its NDEATH was answered or went with it (the
    // will said it then), and this connection's births come now or with the host's STATE.
    death_unacknowledged_ = 0;
    rebirth_pending_ = false;
    // Whatever the host said before this connection may be old: its retained STATE comes
    // again right after our SUBSCRIBE, and births wait for it.
    host_online_ = false;
    host_state_timestamp_ = 0;
    birth();
}

std::size_t SparkplugNode::node_metric(const std::string& name, DataType type) {
    const auto [it, added] = node_metric_of_name_.emplace(name, node_metrics_.size());
    if (added) {
        MetricValue initial =
            type == DataType::string ? MetricValue{std::string()} : MetricValue{counter(0)};
        node_metrics_.push_back({name, type, std::move(initial), false});
    }
    return it->second;
}

void SparkplugNode::set_node_metric(std::size_t index, MetricValue value) {
    auto& metric = node_metrics_[index];
    if (metric.value == value) return;
    metric.value = std::move(value);
    metric.changed = true;
}

bool SparkplugNode::publish(const std::string& topic, adapters::sparkplug::Payload& payload,
                            std::uint64_t ack_token) {
    payload.timestamp_ms = static_cast<std::uint64_t>(clock_.wall_ms());
    payload.seq = seq_;
    message_.topic = topic;
    message_.payload = adapters::sparkplug::encode(payload);
    last_packet_bytes_ = adapters::mqtt::publish_packet_bytes(message_);
    if (last_packet_bytes_ > max_packet_bytes_) {
        // The client would drop it, and a host would see a gap in seq: it never leaves.
        message_.clear();
        return false;
    }
    seq_ = static_cast<std::uint8_t>(seq_ + 1);
    message_.qos = options_.qos;
    message_.retain = false;
    // Every message counts in seq: none may replace another.
    message_.coalesce = false;
    message_.ack_token = ack_token;
    mqtt_.publish(std::move(message_));
    return true;
}

void SparkplugNode::exchanges_changed(const ExchangeSet& running, std::span<const std::string>) {
    std::vector<Device> devices;
    std::unordered_map<const core::plan::ExchangePlan*, std::size_t> of_plan;
    std::unordered_map<std::string, std::size_t> of_name;
    // Node metrics are listed in NBIRTH: those of exchanges are rebuilt, then all are born again.
    node_metrics_.resize(fixed_node_metrics);
    std::erase_if(node_metric_of_name_,
                  [](const auto& entry) { return entry.second >= fixed_node_metrics; });
    const auto add = [&](const core::plan::ExchangePlan* plan, bool produced) {
        Device device;
        // A kept exchange keeps its plan object, and with it its values. The address cannot be
        // a removed exchange's: the gateway destroys those only after this call.
        if (const auto old = device_of_plan_.find(plan); old != device_of_plan_.end()) {
            device = std::move(devices_[old->second]);
        } else {
            device.values.resize(plan->tags.size());
            device.timestamps.resize(plan->tags.size(), 0);
        }
        device.plan = plan;
        device.produced = produced;
        device.alias_base = static_cast<std::uint64_t>(devices.size() + 1) << 32;
        device.born = false;
        const auto prefix = std::string(namespace_prefix) + options_.group_id + "/";
        const auto suffix = "/" + options_.edge_node_id + "/" + plan->spec.name;
        device.birth_topic = prefix + "DBIRTH" + suffix;
        device.data_topic = prefix + "DDATA" + suffix;
        device.death_topic = prefix + "DDEATH" + suffix;
        const auto base = "Exchanges/" + plan->spec.name + "/";
        node_metric(base + "state", DataType::string);
        const auto add_counters = [&](const auto& fields) {
            for (const auto& field : fields) {
                if (field.in(core::in_sparkplug)) {
                    node_metric(base + std::string(field.name), DataType::uint64);
                }
            }
        };
        if (produced) {
            add_counters(core::exchange::produce_counter_fields);
        } else {
            add_counters(core::exchange::consume_counter_fields);
        }
        of_plan.emplace(plan, devices.size());
        of_name.emplace(plan->spec.name, devices.size());
        devices.push_back(std::move(device));
    };
    for (const auto* plan : running.consumed) add(plan, false);
    for (const auto* plan : running.produced) add(plan, true);
    devices_ = std::move(devices);
    device_of_plan_ = std::move(of_plan);
    device_of_name_ = std::move(of_name);
    if (born_) birth();
}

void SparkplugNode::tag_samples(const SampleBatch& batch) {
    const auto found = device_of_plan_.find(&batch.exchange);
    if (found == device_of_plan_.end()) return;
    auto& device = devices_[found->second];
    for (const auto& sample : batch.samples) {
        if (!device.values[sample.tag]) ++device.known;
        device.values[sample.tag] = sample.value;
        device.timestamps[sample.tag] = batch.timestamp_ms;
    }
    if (device.produced && !device.up && device.known == device.values.size()) {
        device.up = true;  // its first datagram: every value is known now
        if (born_) device_birth(device);
        return;
    }
    // A batch of every tag is the JSON tree's republication after its reconnect: the births
    // hold these values already.
    if (!born_ || !device.born || batch.all_tags || batch.quality != core::quality::Quality::good) {
        return;
    }
    publish_data(device, batch, false);
}

bool SparkplugNode::replay(const SampleBatch& batch, std::uint64_t ack_token) {
    const auto found = device_of_plan_.find(&batch.exchange);
    if (found == device_of_plan_.end()) return false;
    const auto& device = devices_[found->second];
    if (!born_ || !device.born || batch.quality != core::quality::Quality::good) return false;
    // Refused for its size, it never will be published: the journal must not wait for it.
    return publish_data(device, batch, true, ack_token);
}

bool SparkplugNode::publish_data(const Device& device, const SampleBatch& batch, bool historical,
                                 std::uint64_t ack_token) {
    payload_.metrics.resize(batch.samples.size());
    for (std::size_t i = 0; i < batch.samples.size(); ++i) {
        const auto& sample = batch.samples[i];
        auto& metric = payload_.metrics[i];
        metric.name.clear();
        metric.alias = device.alias_base + sample.tag;
        metric.timestamp_ms = static_cast<std::uint64_t>(batch.timestamp_ms);
        metric.datatype =
            adapters::sparkplug::datatype_of(batch.exchange.tags[sample.tag].spec.type);
        metric.value = sample.value;
        metric.historical = historical;
        metric.properties.clear();
    }
    if (publish(device.data_topic, payload_, ack_token)) return true;
    data_refused();
    return false;
}

void SparkplugNode::exchange_state(const core::plan::ExchangePlan& exchange,
                                   core::exchange::ConsumeState state) {
    const auto found = device_of_plan_.find(&exchange);
    if (found == device_of_plan_.end()) return;
    auto& device = devices_[found->second];
    if (device.produced) return;
    device.up = state == core::exchange::ConsumeState::ok;
    if (!born_) return;
    if (device.up && !device.born) device_birth(device);
    if (!device.up && device.born) device_death(device);
}

void SparkplugNode::consumed_status(const ConsumedStatus& status) {
    const auto base = "Exchanges/" + status.exchange.spec.name + "/";
    const auto metric = [&](std::string_view name) {
        return node_metric_of_name_.at(base + std::string(name));
    };
    const auto& counters = status.state.counters();
    set_node_metric(metric("state"), std::string(core::exchange::to_string(status.state.state())));
    for (const auto& field : core::exchange::consume_counter_fields) {
        if (field.in(core::in_sparkplug)) {
            set_node_metric(metric(field.name), counter(counters.*field.member));
        }
    }
}

void SparkplugNode::produced_status(const core::plan::ExchangePlan& exchange,
                                    const ProducedStatus& status) {
    const auto base = "Exchanges/" + exchange.spec.name + "/";
    const auto metric = [&](std::string_view name) {
        return node_metric_of_name_.at(base + std::string(name));
    };
    set_node_metric(metric("state"), std::string(status.paused ? "paused" : "producing"));
    for (const auto& field : core::exchange::produce_counter_fields) {
        if (field.in(core::in_sparkplug)) {
            set_node_metric(metric(field.name), counter(status.counters.*field.member));
        }
    }
}

void SparkplugNode::gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) {
    const auto metric = [&](const std::string& name) { return node_metric_of_name_.at(name); };
    set_node_metric(metric("Gateway/uptime_s"),
                    counter(static_cast<std::uint64_t>(uptime.count())));
    set_node_metric(metric("Gateway/datagrams"), counter(sources.datagrams.datagrams));
    set_node_metric(metric("Gateway/accepted"), counter(sources.datagrams.accepted));
    set_node_metric(metric("Gateway/dropped"), counter(sum(sources.datagrams.dropped)));
    for (const auto& field : core::write::write_counter_fields) {
        if (!field.in(core::in_sparkplug)) continue;
        set_node_metric(metric(write_metric_name(field)),
                        counter(core::total(field, sources.writes)));
    }
    if (!born_) return;
    const auto now = static_cast<std::uint64_t>(clock_.wall_ms());
    payload_.metrics.clear();
    for (std::size_t i = 0; i < node_metrics_.size(); ++i) {
        auto& node = node_metrics_[i];
        if (!node.changed) continue;
        payload_.metrics.push_back({{}, i, now, node.type, node.value, false, {}});
        node.changed = false;
    }
    if (!payload_.metrics.empty() && !publish(node_topic("NDATA"), payload_)) data_refused();
}

void SparkplugNode::data_refused() {
    ++stats_.data_refused;
    publish_counters();
}

void SparkplugNode::publish_counters() {
    const auto metric = [&](std::size_t i) { return node_metric_of_name_.at(node_counters[i]); };
    set_node_metric(metric(0), counter(stats_.births_refused));
    set_node_metric(metric(1), counter(stats_.data_refused));
    set_node_metric(metric(2), counter(stats_.rebirth_requests));
    set_node_metric(metric(3), counter(stats_.node_births));
}

}  // namespace eip2mqtt::app::northbound::sparkplug
