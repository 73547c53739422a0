#pragma once
/// From a node's answers to a configuration (`discover --yaml`): what `eip2mqtt discover` learnt
/// of each node on UDP 7937, and the YAML skeleton of the exchanges the nodes produce, in the
/// form `sniff --yaml` prints (adapters::yaml::yaml_skeleton): an `exchanges:` list the loader
/// accepts and `check` passes as it is, every field a node told, what has no key as comments.
/// An exchange a node consumes gets no skeleton, only a comment: a gateway producing it would
/// overwrite what the node reads, which nobody should do from a skeleton of zeros.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/command/exchange_pdus.hpp"

namespace eip2mqtt::adapters::yaml {

/// One exchange a node listed in its Summary, and its Retrieve Configuration, or why not.
struct DiscoveredExchange {
    core::command::SummaryCell cell;
    std::optional<core::command::ExchangeConfig> config;
    std::string problem;  ///< why there is no config: "no answer after 3 attempts"...
};

struct DiscoveredNode {
    std::string address;  ///< as asked, with its port: `10.20.0.7:7937`
    std::optional<core::command::Capabilities> capabilities;
    std::string problem;      ///< why the node told nothing; empty when it answered
    std::uint16_t total = 0;  ///< the exchanges its Summary says it has
    std::vector<DiscoveredExchange> exchanges;
};

/// The skeleton of every exchange `nodes` produce (the first node to list a key wins), then, as
/// comments, the exchanges they consume, those that could not be retrieved, and the nodes that
/// did not answer.
std::string discovered_skeleton(std::span<const DiscoveredNode> nodes);

}  // namespace eip2mqtt::adapters::yaml
