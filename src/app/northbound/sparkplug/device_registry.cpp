// The edge node's devices: built from the running exchanges, their values kept for births,
// their DBIRTH and DDATA metrics filled by alias.

#include "eip2mqtt/app/northbound/sparkplug/device_registry.hpp"

#include <utility>

#include "eip2mqtt/core/plan/published_value.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using adapters::sparkplug::DataType;
using adapters::sparkplug::Metric;
using core::plan::Value;

DataType datatype_of(const core::plan::TagSpec& spec) {
    return adapters::sparkplug::datatype_of(core::plan::published_type(spec), spec.is_array());
}

/// What the metric carries for the raw value `raw`: the tag's published value; is_null where a
/// NaN of a real has no form in the integer type_eu it is published as.
std::optional<adapters::sparkplug::MetricValue> metric_value(const core::plan::TagSpec& spec,
                                                             const Value& raw) {
    auto published = core::plan::published_value(spec, raw).value;
    if (std::holds_alternative<double>(published) &&
        core::plan::is_integer(core::plan::published_type(spec))) {
        return std::nullopt;
    }
    return adapters::sparkplug::MetricValue{std::move(published)};
}

/// Ignition's names where Ignition has one (engUnit, engLow, engHigh, Documentation).
void add_properties(Metric& metric, const core::plan::TagSpec& spec, bool produced) {
    if (!spec.unit().empty()) {
        metric.properties.push_back({"engUnit", DataType::string, spec.unit()});
    }
    if (const auto span = spec.scale() ? core::plan::eu_span(*spec.scale()) : std::nullopt) {
        metric.properties.push_back({"engLow", DataType::float64, Value{span->lo}});
        metric.properties.push_back({"engHigh", DataType::float64, Value{span->hi}});
    }
    if (!spec.description().empty()) {
        metric.properties.push_back({"Documentation", DataType::string, spec.description()});
    }
    if (produced) {
        metric.properties.push_back({"writable", DataType::boolean, Value{spec.writable}});
        if (spec.min()) metric.properties.push_back({"min", DataType::float64, Value{*spec.min()}});
        if (spec.max()) metric.properties.push_back({"max", DataType::float64, Value{*spec.max()}});
    }
}

}  // namespace

DeviceRegistry::DeviceRegistry(std::string group_id, std::string edge_node_id)
    : group_prefix_("spBv1.0/" + group_id + "/"), edge_node_id_(std::move(edge_node_id)) {}

void DeviceRegistry::exchanges_changed(const ExchangeSet& running) {
    std::vector<Device> devices;
    std::unordered_map<const core::plan::ExchangePlan*, std::size_t> of_plan;
    std::unordered_map<std::string, std::size_t> of_name;
    const auto add = [&](const core::plan::ExchangePlan* plan, bool produced) {
        Device device;
        // A kept exchange keeps its plan object, and with it its values. The address cannot be
        // a removed exchange's: the gateway destroys those only after this call.
        if (const auto old = of_plan_.find(plan); old != of_plan_.end()) {
            device = std::move(devices_[old->second]);
        } else {
            device.values.resize(plan->tags.size());
            device.reported.resize(plan->tags.size());
            device.timestamps.resize(plan->tags.size(), 0);
        }
        device.plan = plan;
        device.produced = produced;
        device.alias_base = static_cast<std::uint64_t>(devices.size() + 1) << 32;
        device.born = false;
        const auto suffix = "/" + edge_node_id_ + "/" + plan->spec.name;
        device.birth_topic = group_prefix_ + "DBIRTH" + suffix;
        device.data_topic = group_prefix_ + "DDATA" + suffix;
        device.death_topic = group_prefix_ + "DDEATH" + suffix;
        of_plan.emplace(plan, devices.size());
        of_name.emplace(plan->spec.name, devices.size());
        devices.push_back(std::move(device));
    };
    for (const auto* plan : running.consumed) add(plan, false);
    for (const auto* plan : running.produced) add(plan, true);
    devices_ = std::move(devices);
    of_plan_ = std::move(of_plan);
    of_name_ = std::move(of_name);
}

Device* DeviceRegistry::find(const std::string& name) {
    const auto found = of_name_.find(name);
    return found == of_name_.end() ? nullptr : &devices_[found->second];
}

bool DeviceRegistry::record(Device& device, const SampleBatch& batch) {
    for (const auto& sample : batch.samples) {
        if (!device.values[sample.tag]) ++device.known;
        device.values[sample.tag] = sample.value;
        device.timestamps[sample.tag] = batch.timestamp_ms;
    }
    if (device.produced && !device.up && device.known == device.values.size()) {
        device.up = true;  // its first datagram: every value is known now
        return true;
    }
    return false;
}

std::optional<std::size_t> DeviceRegistry::tag_of(
    const Device& device, const adapters::sparkplug::CommandMetric& metric) {
    const auto& plan = *device.plan;
    if (metric.alias && *metric.alias >= device.alias_base &&
        *metric.alias - device.alias_base < plan.tags.size()) {
        return static_cast<std::size_t>(*metric.alias - device.alias_base);
    }
    if (metric.name.empty()) return std::nullopt;
    for (std::size_t i = 0; i < plan.tags.size(); ++i) {
        if (plan.tags[i].spec.name == metric.name) return i;
    }
    return std::nullopt;
}

void DeviceRegistry::fill_birth(Device& device, adapters::sparkplug::Payload& payload,
                                std::int64_t now_ms) {
    const auto& plan = *device.plan;
    device.reported = device.values;
    payload.metrics.clear();
    payload.metrics.reserve(plan.tags.size());
    for (std::size_t i = 0; i < plan.tags.size(); ++i) {
        const auto& spec = plan.tags[i].spec;
        Metric metric{spec.name,
                      device.alias_base + i,
                      static_cast<std::uint64_t>(device.values[i] ? device.timestamps[i] : now_ms),
                      datatype_of(spec),
                      std::nullopt,
                      false,
                      {}};
        if (device.values[i]) metric.value = metric_value(spec, *device.values[i]);
        add_properties(metric, spec, device.produced);
        payload.metrics.push_back(std::move(metric));
    }
}

void DeviceRegistry::fill_data(Device& device, const SampleBatch& batch, bool historical,
                               adapters::sparkplug::Payload& payload) {
    payload.metrics.resize(batch.samples.size());
    std::size_t filled = 0;
    for (const auto& sample : batch.samples) {
        if (!historical) {
            auto& reported = device.reported[sample.tag];
            if (reported && core::plan::same_value(*reported, sample.value)) continue;
            reported = sample.value;
        }
        auto& metric = payload.metrics[filled++];
        metric.name.clear();
        metric.alias = device.alias_base + sample.tag;
        metric.timestamp_ms = static_cast<std::uint64_t>(batch.timestamp_ms);
        const auto& spec = batch.exchange.tags[sample.tag].spec;
        metric.datatype = datatype_of(spec);
        metric.value = metric_value(spec, sample.value);
        metric.historical = historical;
        metric.properties.clear();
    }
    payload.metrics.resize(filled);
}

}  // namespace eip2mqtt::app::northbound::sparkplug
