// The loader's sections (read_sections.cpp, read_eip.cpp): their keys, defaults and limits.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <string>

#include "tests/adapters/yaml/loading.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

TEST(LoadConfig, Defaults) {
    const auto config = good(minimal_exchange);
    EXPECT_EQ(config.file, "test.yaml");
    EXPECT_EQ(config.gateway.id, "eip2mqtt");
    EXPECT_EQ(config.mqtt.client_id, "eip2mqtt-eip2mqtt");
    EXPECT_EQ(config.mqtt.version, 5);
    ASSERT_EQ(config.exchanges.size(), 1u);
    EXPECT_EQ(config.exchanges[0].spec.topic, "ex");  // defaults to the name
    EXPECT_EQ(config.exchanges[0].spec.direction, Direction::consume);
    EXPECT_FALSE(config.exchanges[0].spec.timeout.has_value());
}

/// A configuration that writes every key of every section but sparkplug's and redundancy's.
constexpr const char* every_section =
    "gateway: { id: gw1, state_dir: /tmp/s, log_level: debug }\n"
    "mqtt:\n"
    "  url: ssl://broker:8883\n"
    "  version: 3.1.1\n"
    "  client_id: me\n"
    "  username: u\n"
    "  password_file: /etc/pw\n"
    "  tls: { ca_file: ca.pem, cert_file: c.pem, key_file: k.pem, verify: false }\n"
    "  base_topic: a/b\n"
    "  qos: 2\n"
    "  retain: false\n"
    "  payload: raw\n"
    "  buffer: { max_messages: 10 }\n"
    "  batch: true\n"
    "  keepalive_s: 15\n"
    "  metrics_interval_s: 5\n"
    "eip:\n"
    "  bind: 127.0.0.1\n"
    "  port: 0\n"
    "  multicast: [ { group: 224.0.7.1, interface: eth0 }, { group: 224.0.7.2 } ]\n"
    "metrics: { listen: 127.0.0.1:9108 }\n"
    "exchanges:\n"
    "  - name: ex\n"
    "    producer_id: 10.0.0.1\n"
    "    exchange_id: 4294967295\n"
    "    length: 200\n"
    "    signature: \"2.5\"\n"
    "    period_ms: 50\n"
    "    timeout_ms: 0\n"
    "    source: 10.0.0.9\n"
    "    topic: area/ex\n"
    "    tags:\n"
    "      - name: T\n"
    "        address: 126\n"
    "        type: WORD\n"
    "        unit: bar\n"
    "        deadband: 0.5\n"
    "        refresh_s: 10\n"
    "        min: 1\n"
    "        max: 2.5\n"
    "        description: free text, ignored\n"
    "  - { name: out, direction: produce, producer_id: 10.0.0.1, exchange_id: 4,\n"
    "      destination: 10.0.0.255, tags: [ { name: B, address: 0.3, type: bool,\n"
    "      writable: yes, initial: true }, { name: R, address: 4.0, type: real, writable:\n"
    "      true, initial: -1.5 }, { name: W, address: 8.0, type: udint, initial: 7 } ] }\n";

void expect_gateway_and_mqtt_of_every_section(const core::config::Config& config) {
    EXPECT_EQ(config.gateway.id, "gw1");
    EXPECT_EQ(config.gateway.state_dir, "/tmp/s");
    EXPECT_EQ(config.gateway.log_level, "debug");
    EXPECT_EQ(config.mqtt.urls, std::vector<std::string>{"ssl://broker:8883"});
    EXPECT_EQ(config.mqtt.version, 3);
    EXPECT_EQ(config.mqtt.client_id, "me");
    EXPECT_EQ(config.mqtt.username, "u");
    EXPECT_EQ(config.mqtt.password_file, "/etc/pw");
    ASSERT_TRUE(config.mqtt.tls.has_value());
    EXPECT_EQ(config.mqtt.tls->ca_file, "ca.pem");
    EXPECT_EQ(config.mqtt.tls->key_file, "k.pem");
    EXPECT_FALSE(config.mqtt.tls->verify);
    EXPECT_EQ(config.mqtt.qos, 2);
    EXPECT_FALSE(config.mqtt.retain);
    EXPECT_EQ(config.mqtt.payload, core::config::PayloadFormat::raw);
    EXPECT_EQ(config.mqtt.buffer_max_messages, 10u);
    EXPECT_TRUE(config.mqtt.batch);
    EXPECT_EQ(config.mqtt.keepalive, std::chrono::seconds(15));
    EXPECT_EQ(config.mqtt.metrics_interval, std::chrono::seconds(5));
}

void expect_eip_and_metrics_of_every_section(const core::config::Config& config) {
    EXPECT_EQ(config.eip.bind, "127.0.0.1");
    EXPECT_EQ(config.eip.port, 0);
    ASSERT_EQ(config.eip.multicast.size(), 2u);
    EXPECT_EQ(config.eip.multicast[0].interface, "eth0");
    EXPECT_EQ(config.eip.multicast[1].group, "224.0.7.2");
    EXPECT_EQ(config.metrics.listen, "127.0.0.1:9108");
}

void expect_exchanges_of_every_section(const core::config::Config& config) {
    ASSERT_EQ(config.exchanges.size(), 2u);
    const auto& ex = config.exchanges[0].spec;
    EXPECT_EQ(ex.exchange_id, 4294967295u);
    EXPECT_EQ(ex.signature, (core::wire::Signature{2, 5}));
    EXPECT_EQ(ex.period, std::chrono::milliseconds(50));
    EXPECT_EQ(ex.timeout, std::chrono::milliseconds(0));
    EXPECT_EQ(ex.source, 0x0A000009u);
    EXPECT_EQ(ex.topic, "area/ex");
    const auto& t = config.exchanges[0].tags.at(0).spec;
    EXPECT_EQ(t.address, (core::plan::Address{126, 0}));
    EXPECT_EQ(t.type, TagType::word);
    EXPECT_EQ(t.unit(), "bar");
    EXPECT_EQ(t.deadband, 0.5);
    EXPECT_EQ(t.refresh, std::chrono::seconds(10));
    EXPECT_EQ(t.min(), 1.0);
    EXPECT_EQ(t.max(), 2.5);
    const auto& out = config.exchanges[1];
    EXPECT_EQ(out.spec.destination, "10.0.0.255");
    ASSERT_EQ(out.tags.size(), 3u);
    EXPECT_EQ(out.tags[0].spec.address, (core::plan::Address{0, 3}));
    EXPECT_TRUE(out.tags[0].spec.writable);
    EXPECT_EQ(out.tags[0].spec.initial(), core::plan::Value{true});
    EXPECT_EQ(out.tags[1].spec.initial(), core::plan::Value{-1.5f});
    EXPECT_EQ(out.tags[2].spec.initial(), core::plan::Value{std::uint64_t{7}});
}

TEST(LoadConfig, EverySection) {
    const auto config = good(every_section);
    expect_gateway_and_mqtt_of_every_section(config);
    expect_eip_and_metrics_of_every_section(config);
    expect_exchanges_of_every_section(config);
}

TEST(LoadConfig, MqttVersionSpellings) {
    for (const char* v : {"5", "\"5\""}) {
        EXPECT_EQ(
            good("mqtt: { version: " + std::string(v) + " }\n" + minimal_exchange).mqtt.version, 5);
    }
    for (const char* v : {"3", "\"3\"", "3.1.1", "\"3.1.1\""}) {
        EXPECT_EQ(
            good("mqtt: { version: " + std::string(v) + " }\n" + minimal_exchange).mqtt.version, 3);
    }
    EXPECT_EQ(bad("mqtt: { version: 4 }\n" + minimal_exchange).size(), 1u);
    EXPECT_EQ(bad("mqtt: { version: three }\n" + minimal_exchange).size(), 1u);
}

TEST(LoadConfig, SparkplugSectionWithItsDefaults) {
    const auto config =
        good("gateway: { id: gw7 }\nsparkplug: { group_id: plant1 }\n" + minimal_exchange);
    EXPECT_TRUE(config.sparkplug.enabled());
    EXPECT_EQ(core::config::sparkplug_node_id(config), "gw7");
    EXPECT_TRUE(config.sparkplug.uns);
    EXPECT_EQ(config.sparkplug.qos, 0);
    EXPECT_TRUE(config.sparkplug.primary_host_id.empty());
    EXPECT_EQ(config.sparkplug.max_packet_bytes, 0u);
    const auto full = good(
        "sparkplug: { group_id: g, edge_node_id: n, primary_host_id: scada, uns: false, qos: 0, "
        "max_packet_bytes: 131072 }\n" +
        minimal_exchange);
    EXPECT_EQ(full.sparkplug.max_packet_bytes, 131072u);
    EXPECT_EQ(core::config::sparkplug_node_id(full), "n");
    EXPECT_EQ(full.sparkplug.primary_host_id, "scada");
    EXPECT_FALSE(full.sparkplug.uns);
    EXPECT_EQ(full.sparkplug.qos, 0);
    EXPECT_FALSE(good(minimal_exchange).sparkplug.enabled());
}

TEST(LoadConfig, InAPairTheEdgeNodeIsThePairsUnlessNamed) {
    const std::string sections =
        "gateway: { id: gw-a }\nredundancy: { pair: turbine }\nsparkplug: { group_id: g";
    EXPECT_EQ(core::config::sparkplug_node_id(good(sections + " }\n" + minimal_exchange)),
              "turbine");
    EXPECT_EQ(core::config::sparkplug_node_id(
                  good(sections + ", edge_node_id: n }\n" + minimal_exchange)),
              "n");
}

TEST(LoadConfig, SparkplugIdsFollowTheTopicElementRules) {
    const auto text =
        dump(bad("sparkplug:\n"
                 "  group_id: plant/1\n"
                 "  edge_node_id: gw+\n"
                 "  primary_host_id: 'sc#ada'\n"
                 "  qos: 2\n"
                 "  uns: maybe\n"
                 "  grop_id: x\n"
                 "  max_packet_bytes: -1\n"
                 "exchanges:\n"
                 "  - { name: area/ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n"));
    EXPECT_NE(text.find("test.yaml:2:3: sparkplug group_id 'plant/1' contains '/', '+' or '#'"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:3:3: sparkplug edge_node_id 'gw+'"), std::string::npos) << text;
    EXPECT_NE(text.find("test.yaml:4:3: sparkplug primary_host_id 'sc#ada'"), std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:5:3: sparkplug qos 2: Sparkplug B 3.0 publishes births and "
                        "data at QoS 0 only"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:6:"), std::string::npos) << text;  // not a boolean
    EXPECT_NE(text.find("test.yaml:8:"), std::string::npos) << text;  // not a size
    EXPECT_NE(text.find("unknown key 'grop_id' in sparkplug (did you mean 'group_id'?)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("exchange name (a Sparkplug device ID) 'area/ex'"), std::string::npos)
        << text;
    // QoS 1 was allowed by earlier releases: refused now, with the reason.
    EXPECT_NE(dump(bad("sparkplug: { group_id: g, qos: 1 }\n" + minimal_exchange))
                  .find("sparkplug qos 1: Sparkplug B 3.0 publishes births and data at QoS 0 only "
                        "(hosts judge an edge node by it); remove the key"),
              std::string::npos);
    // Without group_id there is no Sparkplug: say so rather than ignore the section.
    EXPECT_NE(dump(bad("sparkplug: { edge_node_id: n }\n" + minimal_exchange))
                  .find("sparkplug lacks 'group_id'"),
              std::string::npos);
}

TEST(LoadConfig, StoreAndForwardWithItsDefaultsAndLimits) {
    const auto defaults = good(minimal_exchange).mqtt.store_and_forward;
    EXPECT_FALSE(defaults.enabled);
    EXPECT_EQ(defaults.max_mb, 256u);
    EXPECT_EQ(defaults.replay_rate, 2000u);
    EXPECT_EQ(defaults.fsync_interval, std::chrono::milliseconds(1000));
    const auto full = good(
        "mqtt:\n  store_and_forward: { enabled: true, max_mb: 8, replay_rate: 50, "
        "fsync_interval_ms: 250 }\n" +
        minimal_exchange);
    EXPECT_TRUE(full.mqtt.store_and_forward.enabled);
    EXPECT_EQ(full.mqtt.store_and_forward.max_mb, 8u);
    EXPECT_EQ(full.mqtt.store_and_forward.replay_rate, 50u);
    EXPECT_EQ(full.mqtt.store_and_forward.fsync_interval, std::chrono::milliseconds(250));

    const auto text =
        dump(bad("mqtt:\n"
                 "  store_and_forward:\n"
                 "    enabled: sometimes\n"
                 "    max_mb: 0\n"
                 "    replay_rate: -1\n"
                 "    fsync_interval_ms: 5\n"
                 "    max_bm: 3\n" +
                 minimal_exchange));
    EXPECT_NE(text.find("test.yaml:3:"), std::string::npos) << text;  // not a boolean
    EXPECT_NE(text.find("test.yaml:4:5: 'max_mb' 0 is outside 1.."), std::string::npos) << text;
    EXPECT_NE(text.find("test.yaml:5:5: 'replay_rate' -1 is outside 1.."), std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:6:5: 'fsync_interval_ms' 5 is outside 10.."), std::string::npos)
        << text;
    EXPECT_NE(text.find("unknown key 'max_bm' in mqtt.store_and_forward (did you mean 'max_mb'?)"),
              std::string::npos)
        << text;
    // It replays on the JSON tree: a Sparkplug-only gateway cannot have it.
    EXPECT_NE(dump(bad("mqtt: { store_and_forward: { enabled: true } }\n"
                       "sparkplug: { group_id: g, uns: false }\n" +
                       minimal_exchange))
                  .find("it needs sparkplug uns: true"),
              std::string::npos);
}

TEST(LoadConfig, BatchFirstPutsValuesFirstAndNeedsBatch) {
    EXPECT_FALSE(good(minimal_exchange).mqtt.batch_first);
    EXPECT_TRUE(
        good("mqtt: { batch: true, batch_first: true }\n" + minimal_exchange).mqtt.batch_first);
    const auto text = dump(bad("mqtt:\n  batch_first: true\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:2:3: batch_first puts _values first, and needs batch: true"),
              std::string::npos)
        << text;
}

TEST(LoadConfig, MetricsListenIsOneHostPortNotAList) {
    // civetweb opens a listener per entry of a list: "a,b" passed and listened on both.
    for (const std::string listen :
         {"127.0.0.1:9108,127.0.0.1:9109", "127.0.0.1:9108, 0.0.0.0:9109", "'127.0.0.1 :9108'",
          "127.0.0.1", "9108"}) {
        const auto text = dump(bad("metrics:\n  listen: " + listen + "\n" + minimal_exchange));
        EXPECT_NE(text.find("test.yaml:2:3: listen '"), std::string::npos) << listen << text;
        EXPECT_NE(text.find("' is not one host:port"), std::string::npos) << listen << text;
    }
    EXPECT_EQ(good("metrics: { listen: '[::1]:9108' }\n" + minimal_exchange).metrics.listen,
              "[::1]:9108");
    EXPECT_EQ(good("metrics: { listen: localhost:9108 }\n" + minimal_exchange).metrics.listen,
              "localhost:9108");
}

TEST(LoadConfig, MetricsAuthAndTlsAreReadWholeOrRefused) {
    const auto config = good(
        "metrics:\n  listen: 127.0.0.1:9108\n"
        "  auth: { username: ops, password_file: status-password }\n"
        "  tls: { cert: /etc/eip2mqtt/status.pem, key: /etc/eip2mqtt/status.key }\n" +
        minimal_exchange);
    ASSERT_TRUE(config.metrics.auth.has_value());
    EXPECT_EQ(config.metrics.auth->username, "ops");
    EXPECT_EQ(config.metrics.auth->password_file, "status-password");
    ASSERT_TRUE(config.metrics.tls.has_value());
    EXPECT_EQ(config.metrics.tls->cert, "/etc/eip2mqtt/status.pem");
    EXPECT_EQ(config.metrics.tls->key, "/etc/eip2mqtt/status.key");
    const auto plain = good("metrics: { listen: 127.0.0.1:9108 }\n" + minimal_exchange);
    EXPECT_FALSE(plain.metrics.auth || plain.metrics.tls);

    auto text = dump(
        bad("metrics:\n  listen: 127.0.0.1:9108\n  auth: { username: ops }\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:3:3: metrics.auth needs 'password_file'"), std::string::npos)
        << text;
    text = dump(bad("metrics:\n  listen: 127.0.0.1:9108\n  tls: { }\n" + minimal_exchange));
    EXPECT_NE(text.find("metrics.tls needs 'cert' and 'key'"), std::string::npos) << text;
    text = dump(bad("metrics:\n  auth: { username: ops, password: x }\n" + minimal_exchange));
    EXPECT_NE(text.find("password"), std::string::npos) << text;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
