// yaml_skeleton (`sniff --yaml`): the exact YAML of unconfigured exchanges.

#include "eip2mqtt/adapters/yaml/skeleton.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

namespace exchange = core::exchange;
namespace wire = core::wire;

using namespace std::chrono_literals;
using exchange::ClockState;
using exchange::Destination;
using exchange::DestinationKind;
using exchange::WireSummary;

WireSummary turbine() {
    WireSummary s;
    s.key = {wire::ProducerId{0x0A000009}, 3};  // 10.0.0.9
    s.datagrams = 25;
    s.length = s.min_length = s.max_length = 40;
    s.signature = {1, 0};
    s.period_ms = 20.0126;
    s.period_steps = 24;
    s.destination = {DestinationKind::unicast, 0x7F000001};
    s.clock = ClockState::synced;
    s.clock_offset_ms = 3;
    return s;
}

TEST(YamlSkeleton, NoExchangeIsACommentAlone) {
    EXPECT_EQ(yaml_skeleton({}),
              "# sniff --yaml: no exchange seen on the wire that the configuration lacks\n");
}

TEST(YamlSkeleton, AnExchangeWithEveryFactMeasured) {
    const std::vector<WireSummary> summaries{turbine()};
    EXPECT_EQ(yaml_skeleton(summaries),
              "# sniff --yaml: 1 exchange seen on the wire that the configuration lacks. Rename "
              "at will; add tags where the byte map is known.\n"
              "exchanges:\n"
              "  - name: \"10.0.0.9-3\"\n"
              "    direction: consume\n"
              "    producer_id: 10.0.0.9\n"
              "    exchange_id: 3\n"
              "    length: 40  # data bytes\n"
              "    signature: \"1.0\"\n"
              "    period_ms: 20  # measured 20.013 ms: time between receive times per "
              "request-id step, over 24 steps\n"
              "    topic: \"10-0-0-9/3\"  # under base_topic\n"
              "    # destination: unicast to 127.0.0.1\n"
              "    # clock: synced (the producer's time is 3 ms ahead of the receive time, within "
              "2000 ms)\n"
              "    # seen: 25 datagrams\n"
              "    tags: []  # TODO: the byte map; until then only {topic}/_status is published\n");
}

TEST(YamlSkeleton, WhatCouldNotBeMeasuredOrVariedIsSaid) {
    WireSummary s;
    s.key = {wire::ProducerId{0xC0A80101}, 7};  // 192.168.1.1
    s.datagrams = 1;
    s.length = 10;
    s.min_length = 8;
    s.max_length = 12;
    s.signature_varied = true;  // and the last had none
    s.destination = {DestinationKind::multicast, 0xE0000701};
    s.destination_varied = true;
    s.clock = ClockState::none;
    s.clock_varied = true;
    const std::vector<WireSummary> summaries{s};
    EXPECT_EQ(yaml_skeleton(summaries),
              "# sniff --yaml: 1 exchange seen on the wire that the configuration lacks. Rename "
              "at will; add tags where the byte map is known.\n"
              "exchanges:\n"
              "  - name: \"192.168.1.1-7\"\n"
              "    direction: consume\n"
              "    producer_id: 192.168.1.1\n"
              "    exchange_id: 7\n"
              "    length: 10  # data bytes of the last datagram; lengths 8 to 12 seen: check "
              "which is right\n"
              "    # signature: none (the producer sends 0.0; it varied: the last datagram's)\n"
              "    period_ms: 1000  # TODO: not measured (no two datagrams in sequence); the "
              "default\n"
              "    topic: \"192-168-1-1/7\"  # under base_topic\n"
              "    # destination: multicast group 224.0.7.1 (the gateway joins it with "
              "eip.multicast: [ { group: 224.0.7.1 } ]); it varied: the last datagram's\n"
              "    # clock: none (no timestamp in the datagrams: tags carry the receive time); it "
              "varied: the last datagram's\n"
              "    # seen: 1 datagram\n"
              "    tags: []  # TODO: the byte map; until then only {topic}/_status is published\n");
}

TEST(YamlSkeleton, BroadcastUnsyncedAndAPeriodOutsideTheRange) {
    auto s = turbine();
    s.destination = {DestinationKind::broadcast, 0x0A0000FF};
    s.clock = ClockState::unsynced;
    s.clock_offset_ms = -725000000000;  // a PLC that believes it is the year 2000
    s.period_ms = 0.4;
    s.period_steps = 1;
    s.signature_varied = true;
    auto unknown = turbine();
    unknown.key.exchange_id = 4;
    unknown.destination = {};
    unknown.length = unknown.min_length = unknown.max_length = 0;
    const std::vector<WireSummary> summaries{s, unknown};
    const auto text = yaml_skeleton(summaries);
    for (const auto* line :
         {"# sniff --yaml: 2 exchanges seen on the wire that the configuration lacks.",
          "    signature: \"1.0\"  # it varied: the last datagram's\n",
          "    period_ms: 2  # measured 0.400 ms: time between receive times per request-id "
          "step, over 1 step; period_ms is 2 to 3600000\n",
          "    # destination: broadcast to 10.0.0.255\n",
          "    # clock: unsynced (the producer's time is 725000000000 ms behind the receive time, "
          "beyond 2000 ms: with timestamp auto, tags carry the receive time)\n",
          "  - name: \"10.0.0.9-4\"\n",
          "    length: 1  # TODO: the datagrams carry no data; a length is 1 to 1400 bytes\n",
          "    # destination: unknown (the receiving socket did not say)\n"}) {
        EXPECT_NE(text.find(line), std::string::npos) << line << "\nin:\n" << text;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
