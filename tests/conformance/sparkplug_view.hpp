#pragma once
/// What an edge node put on the wire, as the conformance checks read it: the relays' events of
/// the node's own connections (those whose CONNECT names a client id ending in `-sparkplug`),
/// each connection with its CONNECT, then in order every packet either side sent on it, the
/// node's Sparkplug payloads decoded (the specification's .proto). A view of a recording that a
/// mutation test may alter before the checks read it.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sparkplug_b.pb.h"
#include "tests/support/mqtt_relay.hpp"

namespace eip2mqtt::test::conformance {

using SparkplugPayload = org::eclipse::tahu::protobuf::Payload;

/// One packet of a node's connection: sent by the node (`from_node`) or handed to it.
struct NodePacket {
    bool from_node = true;
    MqttPacket packet;
    /// The Sparkplug payload of a PUBLISH under `spBv1.0/{group}/` (not STATE); nullopt when it
    /// does not decode.
    std::optional<SparkplugPayload> payload;
    std::chrono::steady_clock::time_point at;
};

struct NodeConnection {
    std::size_t relay = 0;       ///< which broker's relay: 0 is the first of mqtt.url
    std::size_t connection = 0;  ///< the relay's number for it
    MqttPacket connect;
    std::vector<NodePacket> packets;  ///< after the CONNECT, in order
    /// The node ended it (its DISCONNECT, or its close first); else the broker, or still open.
    bool closed_by_node = false;
    bool closed = false;  ///< ended: `ended` is its DISCONNECT's time, or its close's
    std::chrono::steady_clock::time_point opened, ended;
};

struct NodeView {
    std::string group = "plant1";
    std::string node = "gw1";
    std::vector<NodeConnection> connections;  ///< in the order they were opened
    /// What the harness did when (the plant going silent, a STATE published...), by name.
    std::map<std::string, std::chrono::steady_clock::time_point> marks;
    /// The run's span in UTC milliseconds: every timestamp the node sends falls in it.
    std::int64_t wall_from_ms = 0, wall_to_ms = 0;

    std::string topic(const std::string& type) const {
        return "spBv1.0/" + group + "/" + type + "/" + node;
    }
    /// The message type of a node topic ("NBIRTH", "DDATA"...); empty for another topic.
    std::string type_of(const std::string& topic_name) const;
};

/// The node's connections of `events` (from any number of relays), each with what passed on it.
NodeView node_view(const std::vector<RelayEvent>& events, std::string group = "plant1",
                   std::string node = "gw1");

/// The value of a metric as an int64 (int_value sign-extended for Int8-Int32, long_value
/// otherwise), for bdSeq and counters.
std::int64_t int_of(const SparkplugPayload::Metric& metric);
/// The first metric of `payload` named `name`, or null.
const SparkplugPayload::Metric* metric_named(const SparkplugPayload& payload,
                                             const std::string& name);

}  // namespace eip2mqtt::test::conformance
