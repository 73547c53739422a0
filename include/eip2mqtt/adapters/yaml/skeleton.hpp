#pragma once
/// From the wire to a configuration (`sniff --yaml`): the YAML of consumed exchanges
/// that were seen on the wire but are not configured, one per summary, as an `exchanges:` list
/// the loader accepts and `check` passes as it is (no tags yet: the gateway then publishes only
/// the exchange's `_status`). Keys carry what the configuration has a key for (producer_id,
/// exchange_id, length, signature, period_ms, a name and topic made from the key); what it has
/// none for (destination, producer clock, how the period was measured, disagreements between
/// datagrams) is written as comments.

#include <span>
#include <string>

#include "eip2mqtt/core/exchange/wire_survey.hpp"

namespace eip2mqtt::adapters::yaml {

/// The skeleton of `exchanges`, in their order: a comment saying what it is, then
/// `exchanges:` with one item each (indented by two spaces). With no exchange, only a comment
/// saying so.
std::string yaml_skeleton(std::span<const core::exchange::WireSummary> exchanges);

/// The topic a skeleton proposes for an exchange: `10-20-0-100/50`, the producer's id with
/// dashes, since some brokers turn a dot into a topic level (RabbitMQ: docs/brokers.md).
std::string skeleton_topic(const core::wire::ExchangeKey& key);

}  // namespace eip2mqtt::adapters::yaml
