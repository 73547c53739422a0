#pragma once
/// The edge node's devices (docs/sparkplug.md): one per running exchange, named after it, its
/// tags its metrics. A tag's alias is its device's alias_base (the device's place, from 1, in
/// the high 32 bits) plus the tag's index. The registry keeps each device's last values for its
/// DBIRTH, and fills the payloads of its DBIRTH and DDATA.
///
/// Pure: the caller publishes what it fills. Threading: the loop only.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

/// One exchange as a device.
struct Device {
    const core::plan::ExchangePlan* plan = nullptr;
    bool produced = false;         ///< writable by DCMD, its plan the ExchangeWrite's handle
    std::uint64_t alias_base = 0;  ///< a tag's alias is alias_base + its index
    std::vector<std::optional<core::plan::Value>> values;
    std::vector<std::int64_t> timestamps;
    /// What the last DBIRTH or live DDATA said of each tag: a DDATA carries only what changed
    /// since (a republication of the JSON tree's `refresh_s` is no change).
    std::vector<std::optional<core::plan::Value>> reported;
    std::size_t known = 0;              ///< values that are set
    bool up = false;                    ///< consumed: state ok; produced: every value known
    bool born = false;                  ///< DBIRTH sent since the last NBIRTH
    bool birth_refused_logged = false;  ///< since its last DBIRTH published
    std::string birth_topic, data_topic, death_topic;
};

class DeviceRegistry {
public:
    DeviceRegistry(std::string group_id, std::string edge_node_id);

    /// The devices of the running exchanges, consumed first, then produced, none born. A kept
    /// exchange (the same plan object) keeps its values; its alias may change with its place.
    void exchanges_changed(const ExchangeSet& running);

    /// The device of `plan`, or nullptr.
    Device* find(const core::plan::ExchangePlan* plan) {
        const auto found = of_plan_.find(plan);
        return found == of_plan_.end() ? nullptr : &devices_[found->second];
    }
    /// The device named `name`, or nullptr.
    Device* find(const std::string& name);
    std::span<Device> devices() { return devices_; }

    /// Keeps `batch`'s values in `device`. True when a produced device is up with it: its first
    /// datagram made every value known.
    static bool record(Device& device, const SampleBatch& batch);
    /// The tag a command's metric names in `device` (by alias, or else by name), or nullopt.
    static std::optional<std::size_t> tag_of(const Device& device,
                                             const adapters::sparkplug::CommandMetric& metric);
    /// `device`'s DBIRTH metrics: every tag by name and alias, with its last value (null if
    /// none yet, stamped `now_ms`) and its properties; what it says is what was reported.
    static void fill_birth(Device& device, adapters::sparkplug::Payload& payload,
                           std::int64_t now_ms);
    /// DDATA metrics of `batch`'s samples by alias: live, those whose value differs from what
    /// was reported (none: an empty payload, nothing to publish); `historical`, every one.
    /// Allocates nothing once `payload` has held a batch as large.
    static void fill_data(Device& device, const SampleBatch& batch, bool historical,
                          adapters::sparkplug::Payload& payload);

private:
    std::string group_prefix_;  ///< "spBv1.0/<group>/"
    std::string edge_node_id_;
    std::vector<Device> devices_;
    std::unordered_map<const core::plan::ExchangePlan*, std::size_t> of_plan_;
    std::unordered_map<std::string, std::size_t> of_name_;
};

}  // namespace eip2mqtt::app::northbound::sparkplug
