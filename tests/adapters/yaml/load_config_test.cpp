#include "eip2mqtt/adapters/yaml/load_config.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <string>

#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml {
namespace {

using core::config::Config;
using core::config::Diagnostics;
using core::plan::Direction;
using core::plan::TagType;

const std::string data = std::string(EIP2MQTT_TEST_DATA) + "/configs/";

std::string dump(const Diagnostics& diagnostics) {
    std::string out;
    for (const auto& d : diagnostics) {
        out += d.mark.file.str() + ":" + std::to_string(d.mark.line) + ":" +
               std::to_string(d.mark.column) + ": " + d.message + "\n";
    }
    return out;
}

/// Loads text that must be valid.
Config good(const std::string& text) {
    auto result = load_config_text(text, "test.yaml");
    EXPECT_TRUE(result.ok()) << dump(result.error());
    return result.ok() ? std::move(result).value() : Config{};
}

/// Loads text that must fail; returns its diagnostics.
Diagnostics bad(const std::string& text) {
    auto result = load_config_text(text, "test.yaml");
    EXPECT_FALSE(result.ok());
    return result.ok() ? Diagnostics{} : result.error();
}

const std::string minimal_exchange =
    "exchanges:\n"
    "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n";

TEST(LoadConfig, ExampleConfigurationLoadsAndValidates) {
    const auto result =
        load_config(std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml");
    ASSERT_TRUE(result.ok()) << dump(result.error());
    const auto& config = result.value();
    EXPECT_EQ(config.gateway.id, "demo-gw");
    EXPECT_EQ(config.mqtt.client_id, "eip2mqtt-demo-gw");
    EXPECT_EQ(config.mqtt.base_topic, "acme/demo");
    EXPECT_EQ(config.eip.port, 18246);
    ASSERT_EQ(config.exchanges.size(), 3u);
    const auto& turbine = config.exchanges[0];
    EXPECT_EQ(turbine.spec.name, "turbine1");
    EXPECT_EQ(turbine.spec.length, 372);
    // The inline tags, then the point list's rows.
    ASSERT_EQ(turbine.tags.size(), 5u + 9u);
    EXPECT_EQ(turbine.tags.back().spec.name, "DENSIDADE_CPO");
    EXPECT_EQ(turbine.tags.back().marks.node.line, 10);
    std::set<TagType> types;
    for (const auto& tag : config.exchanges[1].tags) types.insert(tag.spec.type);
    EXPECT_EQ(types.size(), 9u);  // every type
    EXPECT_EQ(config.exchanges[2].spec.direction, Direction::produce);
    const auto plans = core::config::make_plans(config);
    EXPECT_EQ(plans[0].tags.size(), 14u);
    EXPECT_EQ(plans[0].spec.tags.size(), 14u);
}

TEST(LoadConfig, BadThreeErrorsReportsAllThreeWithLineAndColumn) {
    const auto path = data + "bad_three_errors.yaml";
    const auto result = load_config(path);
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 3u) << dump(d);
    EXPECT_EQ(d[0].mark.file, path);
    EXPECT_EQ(d[0].mark.line, 12);
    EXPECT_EQ(d[0].mark.column, 5);
    EXPECT_EQ(d[0].message,
              "unknown key 'perod_ms' in exchange 'turbine1' (did you mean 'period_ms'?)");
    EXPECT_EQ(d[1].mark.line, 15);
    EXPECT_EQ(d[1].mark.column, 26);
    EXPECT_NE(d[1].message.find("'ON_BITS'"), std::string::npos) << d[1].message;
    EXPECT_NE(d[1].message.find("has a bit number"), std::string::npos) << d[1].message;
    EXPECT_EQ(d[2].mark.line, 16);
    EXPECT_EQ(d[2].mark.column, 26);
    EXPECT_NE(d[2].message.find("past the exchange length 16"), std::string::npos) << d[2].message;
}

TEST(LoadConfig, SyntaxErrorIsADiagnostic) {
    const auto result = load_config(data + "bad_syntax.yaml");
    ASSERT_FALSE(result.ok());
    ASSERT_EQ(result.error().size(), 1u);
    EXPECT_GT(result.error()[0].mark.line, 0);
    EXPECT_NE(result.error()[0].message.find("YAML"), std::string::npos);
}

TEST(LoadConfig, MissingFile) {
    const auto result = load_config(data + "no_such_file.yaml");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().size(), 1u);
}

TEST(LoadConfig, EmptyFile) { EXPECT_EQ(bad("").size(), 1u); }

TEST(LoadConfig, PointListsMergeByNodeWithMarksInTheCsv) {
    const auto result = load_config(data + "points_exchange.yaml");
    ASSERT_TRUE(result.ok()) << dump(result.error());
    const auto& ex = result.value().exchanges;
    ASSERT_EQ(ex.size(), 2u);
    EXPECT_EQ(ex[0].spec.producer_id.value, 0xAC1715B0u);  // 172.23.21.176
    EXPECT_EQ(ex[0].spec.signature, (core::wire::Signature{1, 0}));
    ASSERT_EQ(ex[0].tags.size(), 10u);
    EXPECT_EQ(ex[0].tags[0].spec.name, "EXTRA");
    EXPECT_EQ(ex[0].tags[5].spec.name, "PRESSAO");
    EXPECT_EQ(ex[0].tags[5].spec.type, TagType::int_);
    EXPECT_EQ(ex[0].tags[5].marks.node.file, data + "section6.csv");
    EXPECT_EQ(ex[0].tags[5].marks.node.line, 6);
    ASSERT_EQ(ex[1].tags.size(), 1u);
    EXPECT_EQ(ex[1].tags[0].spec.name, "SPEED_SP");
    EXPECT_TRUE(ex[1].tags[0].spec.writable);
}

TEST(LoadConfig, PointListErrorsPointIntoTheCsv) {
    const auto result = load_config(data + "bad_points.yaml");
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 3u) << dump(d);
    const auto csv = data + "bad_points.csv";
    EXPECT_EQ(d[0].mark.file, csv);
    EXPECT_EQ(d[0].mark.line, 3);  // A again
    EXPECT_NE(d[0].message.find("duplicate tag name 'A'"), std::string::npos) << d[0].message;
    EXPECT_EQ(d[1].mark.line, 4);  // bad address
    EXPECT_EQ(d[1].mark.column, 12);
    EXPECT_EQ(d[2].mark.line, 5);  // Write on a consumed exchange
    EXPECT_NE(d[2].message.find("writable"), std::string::npos);
}

TEST(LoadConfig, MissingPointList) {
    const auto d = bad(
        "exchanges:\n"
        "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8, points: nope.csv }\n");
    ASSERT_EQ(d.size(), 1u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 2);
    EXPECT_EQ(d[0].mark.column, 67);
}

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

TEST(LoadConfig, EverySection) {
    const auto config = good(
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
        "      true, initial: -1.5 }, { name: W, address: 8.0, type: udint, initial: 7 } ] }\n");
    EXPECT_EQ(config.gateway.id, "gw1");
    EXPECT_EQ(config.gateway.state_dir, "/tmp/s");
    EXPECT_EQ(config.gateway.log_level, "debug");
    EXPECT_EQ(config.mqtt.url, "ssl://broker:8883");
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
    EXPECT_EQ(config.eip.bind, "127.0.0.1");
    EXPECT_EQ(config.eip.port, 0);
    ASSERT_EQ(config.eip.multicast.size(), 2u);
    EXPECT_EQ(config.eip.multicast[0].interface, "eth0");
    EXPECT_EQ(config.eip.multicast[1].group, "224.0.7.2");
    EXPECT_EQ(config.metrics.listen, "127.0.0.1:9108");
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

TEST(LoadConfig, UnknownKeysEverywhereWithSuggestions) {
    const auto d =
        bad("gatway: { id: x }\n"               // 1:1
            "mqtt: { qos: 1, retian: true }\n"  // 2:17
            "eip: { prot: 1 }\n"                // 3:8
            "exchanges:\n"
            "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8,\n"
            "      tags: [ { name: A, address: 0, type: bit, color: red } ] }\n");  // 6:49
    ASSERT_EQ(d.size(), 4u) << dump(d);
    EXPECT_EQ(d[0].message, "unknown key 'gatway' at the top level (did you mean 'gateway'?)");
    EXPECT_EQ(d[0].mark.line, 1);
    EXPECT_EQ(d[0].mark.column, 1);
    EXPECT_EQ(d[1].message, "unknown key 'retian' in mqtt (did you mean 'retain'?)");
    EXPECT_EQ(d[1].mark.column, 17);
    EXPECT_EQ(d[2].message, "unknown key 'prot' in eip (did you mean 'port'?)");
    EXPECT_EQ(d[3].message, "unknown key 'color' in tag 'A' of exchange 'ex'");
    EXPECT_EQ(d[3].mark.line, 6);
    EXPECT_EQ(d[3].mark.column, 49);
}

TEST(LoadConfig, TypeErrors) {
    const auto d =
        bad("eip:\n"
            "  port: eighteen\n"
            "mqtt:\n"
            "  retain: maybe\n"
            "  qos: [1]\n"
            "exchanges:\n"
            "  - name: ex\n"
            "    producer_id: 10.0.0.1\n"
            "    exchange_id: 1\n"
            "    length: 8\n"
            "    period_ms: 1.5\n"
            "    tags:\n"
            "      - { name: A, address: 0, type: int, deadband: lots }\n");
    ASSERT_EQ(d.size(), 5u) << dump(d);
    EXPECT_EQ(d[0].message, "expected an integer for 'port'");
    EXPECT_EQ(d[0].mark.line, 2);
    EXPECT_EQ(d[0].mark.column, 3);
    EXPECT_EQ(d[1].message, "expected true or false for 'retain'");
    EXPECT_EQ(d[2].message, "expected an integer for 'qos'");
    EXPECT_EQ(d[3].message, "expected an integer for 'period_ms'");
    EXPECT_EQ(d[4].message, "expected a number for 'deadband'");
}

TEST(LoadConfig, BadValues) {
    const auto d =
        bad("mqtt: { payload: xml }\n"
            "exchanges:\n"
            "  - { name: a, producer_id: 10.0.0.300, exchange_id: 1, length: 8 }\n"
            "  - { name: b, producer_id: 10.0.0.1, exchange_id: 2, length: 8, direction: both }\n"
            "  - name: c\n"
            "    producer_id: 10.0.0.1\n"
            "    exchange_id: 3\n"
            "    signature: 1.2.3\n"
            "    length: 8\n"
            "    tags:\n"
            "      - { name: A, address: 0.8, type: bit }\n"
            "      - { name: B, address: 1, type: float }\n"
            "      - { name: C, type: int }\n");
    ASSERT_EQ(d.size(), 7u) << dump(d);
    EXPECT_NE(d[0].message.find("xml"), std::string::npos);
    EXPECT_NE(d[1].message.find("10.0.0.300"), std::string::npos);
    EXPECT_NE(d[2].message.find("both"), std::string::npos);
    EXPECT_NE(d[3].message.find("1.2.3"), std::string::npos);
    EXPECT_NE(d[4].message.find("0.8"), std::string::npos);
    EXPECT_NE(d[5].message.find("float"), std::string::npos);
    EXPECT_NE(d[6].message.find("lacks 'address'"), std::string::npos);
}

TEST(LoadConfig, ProducerIdDecimalFormAndNumbersForAddressAndSignature) {
    const auto config = good(
        "exchanges:\n"
        "  - name: ex\n"
        "    producer_id: 2954172332\n"
        "    exchange_id: 1\n"
        "    signature: 3\n"
        "    tags: [ { name: A, address: 126.0, type: int }, { name: B, address: 120.7, type: bit "
        "} ]\n");
    const auto& ex = config.exchanges.at(0);
    EXPECT_EQ(core::wire::to_string(ex.spec.producer_id), "172.23.21.176");
    EXPECT_EQ(ex.spec.signature, (core::wire::Signature{3, 0}));
    EXPECT_EQ(ex.tags.at(0).spec.address, (core::plan::Address{126, 0}));
    EXPECT_EQ(ex.tags.at(1).spec.address, (core::plan::Address{120, 7}));
}

TEST(LoadConfig, DuplicateYamlKeys) {
    const auto d = bad("mqtt:\n  qos: 1\n  qos: 2\n" + minimal_exchange);
    ASSERT_EQ(d.size(), 1u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 3);
    EXPECT_NE(d[0].message.find("duplicate key 'qos'"), std::string::npos);
}

TEST(LoadConfig, SemanticChecksUseKeyMarks) {
    const auto d =
        bad("mqtt:\n"
            "  base_topic: acme/+/x\n"
            "exchanges:\n"
            "  - name: ex\n"
            "    producer_id: 10.0.0.1\n"
            "    exchange_id: 1\n"
            "    length: 1401\n"
            "    tags:\n"
            "      - { name: _status, address: 0, type: int, writable: true, min: 5, max: 1 }\n");
    ASSERT_EQ(d.size(), 5u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 2);     // base_topic
    EXPECT_EQ(d[1].mark.line, 7);     // length
    EXPECT_EQ(d[2].mark.column, 11);  // name
    EXPECT_EQ(d[3].mark.column, 49);  // writable
    EXPECT_EQ(d[4].mark.column, 73);  // max
}

TEST(LoadConfig, NulAndControlCharactersWrittenAsYamlEscapesAreRefused) {
    // yaml-cpp turns "\0", "\x00" and "\u0000" into a NUL byte, "\e" into ESC, and "\N" into
    // the lone byte 0x85 (not even UTF-8): each is refused where it was written.
    const auto d = bad(R"(gateway:
  id: "gw\e"
mqtt:
  client_id: "c\0"
  base_topic: "acme\x01"
exchanges:
  - name: "ex\N"
    topic: "t\u0000"
    producer_id: 10.0.0.1
    exchange_id: 1
    length: 8
    tags:
      - { name: "A\0x", address: 0, type: int }
      - { name: "A\x00y", address: 2, type: int }
      - { name: "B\u0085", address: 4, type: int }
)");
    ASSERT_EQ(d.size(), 8u) << dump(d);
    const std::vector<std::pair<int, std::string>> expected{
        {2, "gateway id 'gw\\x1B' contains a control character (it is a topic level)"},
        {4, "client_id 'c\\0' contains a NUL character"},
        {5, "base_topic 'acme\\x01' contains a control character"},
        {7, "exchange name 'ex\\x85' is not valid UTF-8"},
        {8, "exchange 'ex\\x85' topic 't\\0' contains a NUL character"},
        {13, "tag name 'A\\0x' contains a NUL character of exchange 'ex\\x85'"},
        {14, "tag name 'A\\0y' contains a NUL character of exchange 'ex\\x85'"},
        {15, "tag name 'B\\u0085' contains a control character of exchange 'ex\\x85'"}};
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(d[i].mark.line, expected[i].first) << dump(d);
        EXPECT_EQ(d[i].message, expected[i].second);
    }
}

TEST(LoadConfig, RawControlBytesAndInvalidUtf8AreRefused) {
    const auto d = bad(std::string("exchanges:\n"
                                   "  - name: ex\n"
                                   "    producer_id: 10.0.0.1\n"
                                   "    exchange_id: 1\n"
                                   "    tags:\n"
                                   "      - { name: A\x01, address: 0, type: int }\n"
                                   "      - { name: B\xFF") +
                       "C, address: 2, type: int }\n");
    ASSERT_EQ(d.size(), 2u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 6);
    EXPECT_EQ(d[0].message, "tag name 'A\\x01' contains a control character of exchange 'ex'");
    EXPECT_EQ(d[1].mark.line, 7);
    EXPECT_EQ(d[1].message, "tag name 'B\\xFFC' is not valid UTF-8 of exchange 'ex'");
}

TEST(LoadConfig, PointListTagNamesWithControlCharactersAreRefusedAtTheirRows) {
    const test::TempDir dir;
    using namespace std::string_literals;  // "..."s keeps the NULs
    const auto csv = dir.write("p.csv",
                               "TagName,Node,Address,DataType,AccessType\n"
                               "A\0B,ex,0.0,Word,Read\n"
                               "A\0C,ex,2.0,Word,Read\n"
                               "\"\x1B[31mRED\",ex,4.0,Word,Read\n"
                               "OK,ex,6.0,Word,Read\n"s);
    const auto yaml = dir.write("c.yaml",
                                "exchanges:\n"
                                "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, points: "
                                "p.csv }\n");
    const auto result = load_config(yaml);
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 3u) << dump(d);
    for (std::size_t i = 0; i < d.size(); ++i) {
        EXPECT_EQ(d[i].mark.file, csv);
        EXPECT_EQ(d[i].mark.line, static_cast<int>(i) + 2);
    }
    EXPECT_EQ(d[0].message, "tag name 'A\\0B' contains a NUL character of exchange 'ex'");
    EXPECT_EQ(d[1].message, "tag name 'A\\0C' contains a NUL character of exchange 'ex'");
    EXPECT_EQ(d[2].message,
              "tag name '\\x1B[31mRED' contains a control character of exchange 'ex'");
}

TEST(LoadConfig, TopicsLongerThanMqttAllowsAreRefusedInlineAndInPointLists) {
    const test::TempDir dir;
    const std::string long_name(65600, 'L');
    const auto csv = dir.write("p.csv",
                               "TagName,Node,Address,DataType,AccessType\n"
                               "OK,ex,0.0,Word,Read\n" +
                                   std::string(65600, 'M') + ",ex,2.0,Word,Read\n");
    const auto yaml = dir.write("c.yaml",
                                "exchanges:\n"
                                "  - name: ex\n"
                                "    producer_id: 10.0.0.1\n"
                                "    exchange_id: 1\n"
                                "    points: p.csv\n"
                                "    tags:\n"
                                "      - { name: " +
                                    long_name + ", address: 4, type: int }\n");
    const auto result = load_config(yaml);
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 2u) << dump(d);
    // eip2mqtt/ex/{tag}/set/result: 65,600 + 23 bytes.
    const std::string message =
        " of exchange 'ex' makes topic "
        "'{base_topic}/{topic}/{tag}/set/result' 65623 bytes long (MQTT "
        "allows 65535)";
    EXPECT_EQ(d[0].mark.file, yaml);
    EXPECT_EQ(d[0].mark.line, 7);
    EXPECT_EQ(d[0].mark.column, 11);
    const auto shown = [](char c) {
        return "tag '" + std::string(core::config::max_in_quotes_bytes, c) + "...' (65600 bytes)";
    };
    EXPECT_EQ(d[0].message, shown('L') + message);
    EXPECT_EQ(d[1].mark.file, csv);
    EXPECT_EQ(d[1].mark.line, 3);
    EXPECT_EQ(d[1].mark.column, 1);
    EXPECT_EQ(d[1].message, shown('M') + message);
}

/// A configuration in `dir` with one exchange per point list named, `ex1`, `ex2`...: the
/// `points:` key of exchange N (1..9) is on line N + 1, column 68.
std::string points_config(const test::TempDir& dir, const std::vector<std::string>& lists) {
    std::string yaml = "exchanges:\n";
    for (std::size_t i = 0; i < lists.size(); ++i) {
        const auto n = std::to_string(i + 1);
        yaml += "  - { name: ex" + n + ", producer_id: 10.0.0.1, exchange_id: " + n +
                ", length: 8, points: " + lists[i] + " }\n";
    }
    return dir.write("c.yaml", yaml);
}

TEST(LoadConfig, APointListThatIsNotARegularFileIsADiagnosticAtItsKey) {
    // A directory crashed `check` and a reload (std::bad_alloc), a FIFO blocked them for ever,
    // /dev/zero grew the memory without end.
    const test::TempDir dir;
    std::filesystem::create_directory(dir.path() + "/dir.csv");
    ASSERT_EQ(::mkfifo((dir.path() + "/fifo.csv").c_str(), 0600), 0);
    const auto yaml = points_config(dir, {"dir.csv", "fifo.csv", "/dev/zero"});
    const auto result = load_config(yaml);
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 3u) << dump(d);
    for (std::size_t i = 0; i < d.size(); ++i) {
        EXPECT_EQ(d[i].mark.file, yaml);
        EXPECT_EQ(d[i].mark.line, static_cast<int>(i) + 2);
        EXPECT_EQ(d[i].mark.column, 68);
    }
    EXPECT_EQ(d[0].message,
              "point list '" + dir.path() + "/dir.csv' is not a regular file (a directory)");
    EXPECT_EQ(d[1].message,
              "point list '" + dir.path() + "/fifo.csv' is not a regular file (a FIFO)");
    EXPECT_EQ(d[2].message, "point list '/dev/zero' is not a regular file (a character device)");
}

TEST(LoadConfig, APointListOverTheSizeLimitIsADiagnosticAtItsKey) {
    const test::TempDir dir;
    // A valid list padded to the limit exactly by a comment line (sparse: nothing is written).
    const std::string list = "TagName,Node,Address,DataType,AccessType\nA,ex1,0.0,Word,Read\n#";
    dir.write("limit.csv", list);
    std::filesystem::resize_file(dir.path() + "/limit.csv", max_file_bytes);
    dir.write("over.csv", list);
    std::filesystem::resize_file(dir.path() + "/over.csv", max_file_bytes + 1);
    dir.write("huge.csv", list);
    std::filesystem::resize_file(dir.path() + "/huge.csv", 70000000);

    auto result = load_config(points_config(dir, {"limit.csv"}));
    ASSERT_TRUE(result.ok()) << dump(result.error());
    ASSERT_EQ(result.value().exchanges.at(0).tags.size(), 1u);

    result = load_config(points_config(dir, {"over.csv", "huge.csv"}));
    ASSERT_FALSE(result.ok());
    const auto& d = result.error();
    ASSERT_EQ(d.size(), 2u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 2);
    EXPECT_EQ(d[0].mark.column, 68);
    EXPECT_EQ(d[0].message, "point list '" + dir.path() +
                                "/over.csv' is 67108865 bytes; the limit is 67108864 (64 MiB)");
    EXPECT_EQ(d[1].mark.line, 3);
    EXPECT_EQ(d[1].message, "point list '" + dir.path() +
                                "/huge.csv' is 70000000 bytes; the limit is 67108864 (64 MiB)");
}

TEST(LoadConfig, AConfigurationThatIsNotARegularFileOrTooBigIsADiagnosticWithoutLine) {
    const test::TempDir dir;
    ASSERT_EQ(::mkfifo((dir.path() + "/fifo.yaml").c_str(), 0600), 0);
    const auto big = dir.write("big.yaml", minimal_exchange + "#");
    std::filesystem::resize_file(big, max_file_bytes + 1);
    const std::vector<std::pair<std::string, std::string>> cases{
        {dir.path(), "the configuration is not a regular file (a directory)"},
        {dir.path() + "/fifo.yaml", "the configuration is not a regular file (a FIFO)"},
        {"/dev/zero", "the configuration is not a regular file (a character device)"},
        {big, "the configuration is 67108865 bytes; the limit is 67108864 (64 MiB)"}};
    for (const auto& [path, message] : cases) {
        const auto result = load_config(path);
        ASSERT_FALSE(result.ok()) << path;
        ASSERT_EQ(result.error().size(), 1u) << dump(result.error());
        EXPECT_EQ(result.error()[0].to_string(), path + ": error: " + message);
    }
}

TEST(LoadConfig, MissingIdentityKeysDropTheExchangeWithoutEchoes) {
    // Without its exchange_id, `b` is left out: no duplicate-pair echo against `a`.
    const auto d =
        bad("exchanges:\n"
            "  - { name: a, producer_id: 10.0.0.1, exchange_id: 0, length: 8 }\n"
            "  - { name: b, producer_id: 10.0.0.1, length: 8 }\n");
    ASSERT_EQ(d.size(), 1u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 3);
    EXPECT_NE(d[0].message.find("lacks 'exchange_id'"), std::string::npos);
}

}  // namespace
}  // namespace eip2mqtt::adapters::yaml

namespace eip2mqtt::adapters::yaml {
namespace {

TEST(LoadConfig, SparkplugSectionWithItsDefaults) {
    const auto config =
        good("gateway: { id: gw7 }\nsparkplug: { group_id: plant1 }\n" + minimal_exchange);
    EXPECT_TRUE(config.sparkplug.enabled());
    EXPECT_EQ(config.sparkplug.node_id(config.gateway), "gw7");
    EXPECT_TRUE(config.sparkplug.uns);
    EXPECT_EQ(config.sparkplug.qos, 0);
    EXPECT_TRUE(config.sparkplug.primary_host_id.empty());
    EXPECT_EQ(config.sparkplug.max_packet_bytes, 0u);
    const auto full = good(
        "sparkplug: { group_id: g, edge_node_id: n, primary_host_id: scada, uns: false, qos: 1, "
        "max_packet_bytes: 131072 }\n" +
        minimal_exchange);
    EXPECT_EQ(full.sparkplug.max_packet_bytes, 131072u);
    EXPECT_EQ(full.sparkplug.node_id(full.gateway), "n");
    EXPECT_EQ(full.sparkplug.primary_host_id, "scada");
    EXPECT_FALSE(full.sparkplug.uns);
    EXPECT_EQ(full.sparkplug.qos, 1);
    EXPECT_FALSE(good(minimal_exchange).sparkplug.enabled());
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
    EXPECT_NE(text.find("test.yaml:5:"), std::string::npos) << text;  // qos 0 or 1
    EXPECT_NE(text.find("test.yaml:6:"), std::string::npos) << text;  // not a boolean
    EXPECT_NE(text.find("test.yaml:8:"), std::string::npos) << text;  // not a size
    EXPECT_NE(text.find("unknown key 'grop_id' in sparkplug (did you mean 'group_id'?)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("exchange name (a Sparkplug device ID) 'area/ex'"), std::string::npos)
        << text;
    // Without group_id there is no Sparkplug: say so rather than ignore the section.
    EXPECT_NE(dump(bad("sparkplug: { edge_node_id: n }\n" + minimal_exchange))
                  .find("sparkplug lacks 'group_id'"),
              std::string::npos);
}

}  // namespace
}  // namespace eip2mqtt::adapters::yaml

namespace eip2mqtt::adapters::yaml {
namespace {

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

}  // namespace
}  // namespace eip2mqtt::adapters::yaml
