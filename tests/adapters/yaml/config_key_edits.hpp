#pragma once
// The configuration file that writes every key, and an edit of each key alone in it, with what
// a reload plan must name for it (config_keys_test.cpp).

#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/core/config/reload_plan.hpp"

namespace eip2mqtt::adapters::yaml::test_keys {

using Kind = core::config::KeyChange::Kind;

/// A file that writes every key, each value on a line of its own.
inline const std::string complete = R"(gateway:
  id: gw1
  state_dir: /var/lib/eip2mqtt-a
  log_level: info
  timestamp: auto
  clock_tolerance_ms: 2000
  location: { enterprise: acme }
mqtt:
  url: tcp://broker-a:1883
  version: 5
  client_id: client-a
  username: user-a
  password_file: /etc/eip2mqtt/password-a
  tls:
    ca_file: /etc/ca-a.pem
    cert_file: /etc/cert-a.pem
    key_file: /etc/key-a.pem
    verify: true
  base_topic: plant-a
  topic_template: "{base}/{enterprise}/{exchange}/{tag}"
  qos: 1
  retain: true
  payload: json
  buffer:
    max_messages: 1000
  batch: true
  batch_first: false
  keepalive_s: 30
  metrics_interval_s: 10
  session_expiry_s: 0
  allow_response_topics_under_base: false
  properties: [unit, quality]
  message_expiry_s: 0
  topic_aliases: false
  describe_payloads: true
  store_and_forward:
    enabled: false
    max_mb: 64
    replay_rate: 2000
    fsync_interval_ms: 1000
eip:
  bind: 0.0.0.0
  port: 18246
  multicast:
    - group: 239.1.1.1
      interface: eth0
  multicast_ttl: 1
  multicast_interface: 10.0.0.9
  link_mbps: 100
  commands:
    enabled: true
    port: 7937
    allow: [ 10.20.0.0/24 ]
    trusted: [ 10.30.0.0/24 ]
    writes: false
    max_requests_per_s: 100
    max_requests_per_s_per_source: 20
metrics:
  listen: 127.0.0.1:9108
  auth: { username: ops-a, password_file: status-password }
  tls: { cert: /etc/status-a.pem, key: /etc/status-a.key }
sparkplug:
  group_id: plant
  edge_node_id: node-a
  primary_host_id: scada-a
  uns: true
  connection: mqtt
  qos: 0
  max_packet_bytes: 65536
redundancy:
  pair: turbine-gw
  takeover_ms: 2000
  priority: 100
exchanges:
  - name: consumed
    direction: consume
    producer_id: 10.0.0.1
    exchange_id: 1
    length: 16
    signature: 1.0
    period_ms: 1000
    timeout_ms: 3000
    timestamp: producer
    clock_tolerance_ms: 500
    source: 10.0.0.7
    topic: area/consumed
    location: { area: hall }
    points: points-a.csv
    tags:
      - { name: SPEED, address: 0.0, type: real }
      - { name: TEXT, address: 10.0, type: string, length: 4, trim: true }
  - name: produced
    direction: produce
    producer_id: 10.0.0.2
    exchange_id: 2
    period_ms: 200
    destination: 10.0.0.3:18246
    publish_raw: true
    tags:
      - name: VALUE
        address: 8.0
        type: dint
        count: 2
        unit: rpm
        deadband: 0.5
        refresh_s: 60
        writable: true
        min: 0
        max: 1000
        initial: 5
        description: a setpoint
        max_writes_per_s: 10
        scale: { gain: 1, offset: 0 }
        type_eu: lreal
        publish_raw: false
        location: { asset: p1 }
        topic_name: value
        topic: plant-a/custom/value
  - { name: spare, direction: consume, producer_id: 10.0.0.4, exchange_id: 4, length: 2 }
)";

inline const std::string points =
    "TagName,Node,Address,DataType,AccessType\nFLOW,consumed,4.0,Real,Read\n";

struct Edit {
    std::string key;   ///< the table's key: `mqtt.url`, `exchanges[].period_ms`...
    std::string from;  ///< text of `complete`, found once
    std::string to;
    /// What the plan names; empty: the key itself, changed.
    std::vector<std::pair<std::string, Kind>> named = {};
    /// The key takes one value only (kept so that older files load): any other is refused, with
    /// this text in the message.
    std::string refused = {};
};

inline const std::vector<Edit> edits = {
    {"gateway.id", "  id: gw1\n", "  id: gw2\n"},
    {"gateway.state_dir", "eip2mqtt-a\n", "eip2mqtt-b\n"},
    {"gateway.log_level", "log_level: info", "log_level: debug"},
    {"gateway.timestamp", "timestamp: auto", "timestamp: receive"},
    {"gateway.clock_tolerance_ms", "clock_tolerance_ms: 2000", "clock_tolerance_ms: 3000"},
    {"gateway.location", "enterprise: acme", "enterprise: acme2"},
    {"mqtt.name", "mqtt:\n  url:", "mqtt:\n  name: mqtt\n  url:"},
    {"mqtt.writes", "  retain: true\n", "  retain: true\n  writes: false\n"},
    {"mqtt.url", "broker-a", "broker-b"},
    {"mqtt.version", "version: 5", "version: 3.1.1"},
    {"mqtt.client_id", "client-a", "client-b"},
    {"mqtt.username", "user-a", "user-b"},
    {"mqtt.password_file", "password-a", "password-b"},
    {"mqtt.tls",
     "  tls:\n    ca_file: /etc/ca-a.pem\n    cert_file: /etc/cert-a.pem\n"
     "    key_file: /etc/key-a.pem\n    verify: true\n",
     ""},
    {"mqtt.tls.ca_file", "ca-a.pem", "ca-b.pem"},
    {"mqtt.tls.cert_file", "cert-a.pem", "cert-b.pem"},
    {"mqtt.tls.key_file", "key-a.pem", "key-b.pem"},
    {"mqtt.tls.verify", "verify: true", "verify: false"},
    {"mqtt.base_topic", "base_topic: plant-a", "base_topic: plant-b"},
    {"mqtt.topic_template", "{base}/{enterprise}/{exchange}/{tag}",
     "{base}/{exchange}/{enterprise}/{tag}"},
    {"mqtt.qos", "qos: 1", "qos: 0"},
    {"mqtt.properties", "[unit, quality]", "[unit]"},
    {"mqtt.message_expiry_s", "message_expiry_s: 0", "message_expiry_s: 60"},
    {"mqtt.topic_aliases", "topic_aliases: false", "topic_aliases: true"},
    {"mqtt.describe_payloads", "describe_payloads: true", "describe_payloads: false"},
    {"mqtt.retain", "retain: true", "retain: false"},
    {"mqtt.payload", "payload: json", "payload: raw"},
    {"mqtt.buffer.max_messages", "max_messages: 1000", "max_messages: 2000"},
    {"mqtt.batch", "batch: true", "batch: false"},
    {"mqtt.batch_first", "batch_first: false", "batch_first: true"},
    {"mqtt.keepalive_s", "keepalive_s: 30", "keepalive_s: 60"},
    {"mqtt.metrics_interval_s", "metrics_interval_s: 10", "metrics_interval_s: 20"},
    {"mqtt.session_expiry_s", "session_expiry_s: 0", "session_expiry_s: 60"},
    {"mqtt.allow_response_topics_under_base", "under_base: false", "under_base: true"},
    {"mqtt.store_and_forward.enabled", "enabled: false", "enabled: true"},
    {"mqtt.store_and_forward.max_mb", "max_mb: 64", "max_mb: 128"},
    {"mqtt.store_and_forward.replay_rate", "replay_rate: 2000", "replay_rate: 3000"},
    {"mqtt.store_and_forward.fsync_interval_ms", "fsync_interval_ms: 1000",
     "fsync_interval_ms: 2000"},
    {"eip.bind", "bind: 0.0.0.0", "bind: 127.0.0.1"},
    {"eip.port", "port: 18246", "port: 18247"},
    {"eip.multicast",
     "      interface: eth0\n",
     "      interface: eth0\n    - group: 239.1.1.2\n",
     {{"eip.multicast", Kind::changed}}},
    {"eip.multicast.group", "239.1.1.1", "239.1.1.3", {{"eip.multicast", Kind::changed}}},
    {"eip.multicast.interface",
     "interface: eth0",
     "interface: eth1",
     {{"eip.multicast", Kind::changed}}},
    {"eip.multicast_ttl", "multicast_ttl: 1", "multicast_ttl: 2"},
    {"eip.multicast_interface", "10.0.0.9", "10.0.0.8"},
    {"eip.link_mbps", "link_mbps: 100", "link_mbps: 1000"},
    {"eip.commands.enabled", "    enabled: true\n", "    enabled: false\n"},
    {"eip.commands.port", "port: 7937", "port: 7938"},
    {"eip.commands.allow", "10.20.0.0/24", "10.20.1.0/24"},
    {"eip.commands.writes", "writes: false", "writes: true"},
    {"eip.commands.trusted", "10.30.0.0/24", "10.30.1.0/24"},
    {"eip.commands.max_requests_per_s", "max_requests_per_s: 100", "max_requests_per_s: 200"},
    {"eip.commands.max_requests_per_s_per_source", "max_requests_per_s_per_source: 20",
     "max_requests_per_s_per_source: 30"},
    {"metrics.listen", "127.0.0.1:9108", "127.0.0.1:9109"},
    {"metrics.auth", "ops-a", "ops-b"},
    {"metrics.tls", "status-a.pem", "status-b.pem"},
    {"sparkplug.group_id", "group_id: plant", "group_id: plant-b"},
    {"sparkplug.edge_node_id", "node-a", "node-b"},
    {"sparkplug.primary_host_id", "scada-a", "scada-b"},
    {"sparkplug.uns", "uns: true", "uns: false"},
    {"sparkplug.connection", "connection: mqtt", "connection: \"\""},
    {"sparkplug.qos", "qos: 0", "qos: 1", {}, "sparkplug qos 1: Sparkplug B 3.0 publishes"},
    {"sparkplug.max_packet_bytes", "max_packet_bytes: 65536", "max_packet_bytes: 32768"},
    {"redundancy.pair", "pair: turbine-gw", "pair: boiler-gw"},
    {"redundancy.takeover_ms", "takeover_ms: 2000", "takeover_ms: 3000"},
    {"redundancy.priority", "priority: 100", "priority: 50"},
    // A new name is another exchange: started, and the old one stopped.
    {"exchanges[].name",
     "name: produced",
     "name: renamed",
     {{"exchanges[renamed]", Kind::added}, {"exchanges[produced]", Kind::removed}}},
    // A produced exchange needs a destination, which a consumed one may not have.
    {"exchanges[].direction",
     "direction: consume, producer_id: 10.0.0.4",
     "direction: produce, destination: 10.0.0.5, producer_id: 10.0.0.4",
     {{"exchanges[spare].direction", Kind::changed},
      {"exchanges[spare].destination", Kind::changed}}},
    {"exchanges[].producer_id",
     "producer_id: 10.0.0.1",
     "producer_id: 10.0.0.11",
     {{"exchanges[consumed].producer_id", Kind::changed}}},
    {"exchanges[].exchange_id",
     "exchange_id: 1\n",
     "exchange_id: 5\n",
     {{"exchanges[consumed].exchange_id", Kind::changed}}},
    {"exchanges[].length",
     "length: 16",
     "length: 20",
     {{"exchanges[consumed].length", Kind::changed}}},
    {"exchanges[].signature",
     "signature: 1.0",
     "signature: 1.1",
     {{"exchanges[consumed].signature", Kind::changed}}},
    {"exchanges[].period_ms",
     "period_ms: 1000",
     "period_ms: 500",
     {{"exchanges[consumed].period_ms", Kind::changed}}},
    {"exchanges[].timeout_ms",
     "timeout_ms: 3000",
     "timeout_ms: 4000",
     {{"exchanges[consumed].timeout_ms", Kind::changed}}},
    {"exchanges[].timestamp",
     "timestamp: producer",
     "timestamp: receive",
     {{"exchanges[consumed].timestamp", Kind::changed}}},
    {"exchanges[].clock_tolerance_ms",
     "clock_tolerance_ms: 500",
     "clock_tolerance_ms: 600",
     {{"exchanges[consumed].clock_tolerance_ms", Kind::changed}}},
    {"exchanges[].source",
     "source: 10.0.0.7",
     "source: 10.0.0.8",
     {{"exchanges[consumed].source", Kind::changed}}},
    {"exchanges[].destination",
     "10.0.0.3:18246",
     "10.0.0.3:18247",
     {{"exchanges[produced].destination", Kind::changed}}},
    {"exchanges[].topic",
     "area/consumed",
     "area/other",
     {{"exchanges[consumed].topic", Kind::changed}}},
    {"exchanges[].location",
     "area: hall",
     "area: yard",
     {{"exchanges[consumed].location", Kind::changed}}},
    // Another file with the same rows: only the key changed.
    {"exchanges[].points",
     "points-a.csv",
     "points-b.csv",
     {{"exchanges[consumed].points", Kind::changed}}},
    // VALUE says its own publish_raw: only the exchange's key changes.
    {"exchanges[].publish_raw",
     "publish_raw: true",
     "publish_raw: false",
     {{"exchanges[produced].publish_raw", Kind::changed}}},
    {"exchanges[].tags[].length",
     "length: 4",
     "length: 6",
     {{"exchanges[consumed].tags[TEXT].length", Kind::changed}}},
    {"exchanges[].tags[].trim",
     "trim: true",
     "trim: false",
     {{"exchanges[consumed].tags[TEXT].trim", Kind::changed}}},
    // `initial: 5` is one value for every element: it has one more.
    {"exchanges[].tags[].count",
     "count: 2",
     "count: 3",
     {{"exchanges[produced].tags[VALUE].initial", Kind::changed},
      {"exchanges[produced].tags[VALUE].count", Kind::changed}}},
    {"exchanges[].tags[].name",
     "name: VALUE",
     "name: VALUE2",
     {{"exchanges[produced].tags[VALUE2]", Kind::added},
      {"exchanges[produced].tags[VALUE]", Kind::removed}}},
};

/// The tag keys, all edited on the produced exchange's VALUE.
inline const std::vector<Edit> tag_edits = {
    {"address", "address: 8.0", "address: 12.0"},
    // Both signed: `initial` reads as the same value.
    {"type", "type: dint", "type: int"},
    {"unit", "unit: rpm", "unit: rev/min"},
    {"deadband", "deadband: 0.5", "deadband: 1.5"},
    {"refresh_s", "refresh_s: 60", "refresh_s: 30"},
    {"writable", "writable: true", "writable: false"},
    {"min", "min: 0", "min: 1"},
    {"max", "max: 1000", "max: 2000"},
    {"initial", "initial: 5", "initial: 6"},
    {"description", "a setpoint", "the setpoint"},
    {"max_writes_per_s", "max_writes_per_s: 10", "max_writes_per_s: 20"},
    // `initial: 5` stays raw 5 (5 / 1.01 rounds to 5): only the scale changes.
    {"scale", "gain: 1,", "gain: 1.01,"},
    {"type_eu", "type_eu: lreal", "type_eu: dint"},
    {"publish_raw", "publish_raw: false", "publish_raw: true"},
    {"location", "asset: p1", "asset: p2"},
    {"topic_name", "topic_name: value", "topic_name: value2"},
    {"topic", "custom/value", "custom/value2"},
};

inline std::vector<Edit> every_edit() {
    auto all = edits;
    for (const auto& edit : tag_edits) {
        const std::string path = "exchanges[produced].tags[VALUE]." + edit.key;
        all.push_back(
            {"exchanges[].tags[]." + edit.key, edit.from, edit.to, {{path, Kind::changed}}});
    }
    return all;
}

}  // namespace eip2mqtt::adapters::yaml::test_keys
