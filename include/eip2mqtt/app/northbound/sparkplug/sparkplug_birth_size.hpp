#pragma once
/// How large the Sparkplug births of a configuration can grow, for `check`: a birth over the
/// broker's Maximum Packet Size is never published, so the node or that device is never born
/// (docs/sparkplug.md "Packet size").

#include <cstddef>
#include <span>
#include <vector>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

/// The most bytes each birth's PUBLISH packet can take (adapters::mqtt::publish_packet_bytes),
/// every value and counter at its widest encoding.
struct SparkplugBirthSizes {
    std::size_t node = 0;              ///< NBIRTH
    std::vector<std::size_t> devices;  ///< the DBIRTH of each plan, in the order given
};

/// Built by a SparkplugNode of `options` over `plans`, as the gateway would build them.
SparkplugBirthSizes sparkplug_birth_sizes(const SparkplugOptions& options,
                                          std::span<const core::plan::ExchangePlan> plans);

/// 128 KiB: the limit `check` holds births against when `sparkplug.max_packet_bytes` is not
/// set; some cloud brokers take no larger packet.
inline constexpr std::size_t common_max_packet_bytes = 131072;

}  // namespace eip2mqtt::app::northbound::sparkplug
