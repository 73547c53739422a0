#include "eip2mqtt/adapters/yaml/load_config.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <stop_token>
#include <string>

#include "tests/adapters/yaml/loading.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

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
    EXPECT_EQ(types.size(), 10u);  // every type, string included
    EXPECT_EQ(config.exchanges[2].spec.direction, Direction::produce);
    const auto plans = core::config::make_plans(config);
    EXPECT_EQ(plans[0].tags.size(), 14u);
    EXPECT_EQ(plans[0].spec.tags.size(), 14u);
}

TEST(LoadConfig, AStopRequestedGivesTheLoadUpWithADiagnostic) {
    // A reload's parse when the gateway stops (ReloadWorker): the file is not read to its end.
    const auto path = std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml";
    std::stop_source stop;
    ASSERT_TRUE(load_config(path, stop.get_token()).ok());  // not requested: loads as always
    stop.request_stop();
    const auto result = load_config(path, stop.get_token());
    ASSERT_FALSE(result.ok());
    ASSERT_EQ(result.error().size(), 1u) << dump(result.error());
    EXPECT_NE(result.error()[0].message.find("given up: the gateway is stopping"),
              std::string::npos)
        << dump(result.error());
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
        {4, "client_id 'c\\x00' contains a NUL character"},
        {5, "base_topic 'acme\\x01' contains a control character"},
        {7, "exchange name 'ex\\x85' is not valid UTF-8"},
        {8, "exchange 'ex\\x85' topic 't\\x00' contains a NUL character"},
        {13, "tag name 'A\\x00x' contains a NUL character of exchange 'ex\\x85'"},
        {14, "tag name 'A\\x00y' contains a NUL character of exchange 'ex\\x85'"},
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

TEST(LoadConfig, ATabInTheIndentationIsNamed) {
    const auto d =
        bad("gateway:\n"
            "  id: gw\n"
            "mqtt:\n"
            "\turl: tcp://127.0.0.1:1\n");
    ASSERT_EQ(d.size(), 1u) << dump(d);
    EXPECT_NE(d[0].message.find("tab"), std::string::npos) << d[0].message;
    EXPECT_EQ(d[0].mark.line, 4) << d[0].message;
    EXPECT_EQ(d[0].mark.column, 1) << d[0].message;
}

TEST(LoadConfig, ARawNulByteIsNamedAtItsLineAndColumn) {
    // yaml-cpp said "bad character found while scanning hex number", two lines further on.
    const std::string text = std::string("exchanges:\n  - name: ex\n    topic: a") + '\0' +
                             "b\n    producer_id: 10.0.0.1\n    exchange_id: 1\n"
                             "    tags:\n      - { name: A, address: \"0.0\", type: dint }\n";
    const auto text_out = dump(bad(text));
    EXPECT_EQ(text_out,
              "test.yaml:3:13: YAML syntax error: a NUL byte (\\x00) in the file; YAML allows "
              "none\n");
    EXPECT_NE(dump(bad(std::string("\0", 1))).find("test.yaml:1:1: "), std::string::npos);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
