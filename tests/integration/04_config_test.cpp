// `check` reports every configuration error with line and column; `run` refuses a bad file;
// the example configuration in etc/ is valid.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string bad_config = R"(gateway:
  id: gw
mqtt:
  url: tcp://127.0.0.1:1
  base_topic: test
exchanges:
  - name: unit1
    direction: consume
    producer_id: 10.0.0.1
    exchange_id: 1
    length: 8
    period_ms: 100
    colour: blue
    tags:
      - { name: A, address: "0.0", type: dint }
      - { name: B, address: "2.3", type: int }
      - { name: C, address: "7.0", type: int }
)";

TEST(CheckCommand, ReportsBitOnIntPastEndAndUnknownKeyWithLineAndColumn) {
    TempDir dir;
    const auto path = dir.write("bad.yaml", bad_config);
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find(path + ":13:5:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("colour"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(path + ":16:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("has a bit number"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(path + ":17:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("past"), std::string::npos) << result.output;
}

TEST(CheckCommand, RefusesPointListsThatAreNoRegularFilesOrTooBigAtTheirKeyWithoutHanging) {
    // A directory crashed `check` (std::bad_alloc, no file:line), a FIFO blocked it for ever.
    TempDir dir;
    std::filesystem::create_directory(dir.path() + "/dir.csv");
    ASSERT_EQ(::mkfifo((dir.path() + "/fifo.csv").c_str(), 0600), 0);
    const auto huge = dir.write("huge.csv", "TagName,Node,Address,DataType,AccessType\n#");
    std::filesystem::resize_file(huge, 70000000);  // sparse
    std::string yaml = "exchanges:\n";
    int id = 0;
    for (const char* points : {"dir.csv", "fifo.csv", "/dev/zero", "huge.csv"}) {
        ++id;
        yaml += "  - name: ex" + std::to_string(id) + "\n    producer_id: 10.0.0.1\n" +
                "    exchange_id: " + std::to_string(id) +
                "\n    length: 8\n    points: " + points + "\n";
    }
    const auto path = dir.write("points.yaml", yaml);
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    for (const std::string& expected :
         {path + ":6:5: error: point list '" + dir.path() +
              "/dir.csv' is not a regular file (a directory)",
          path + ":11:5: error: point list '" + dir.path() +
              "/fifo.csv' is not a regular file (a FIFO)",
          path + ":16:5: error: point list '/dev/zero' is not a regular file (a character device)",
          path + ":21:5: error: point list '" + dir.path() +
              "/huge.csv' is 70000000 bytes; the limit is 67108864 (64 MiB)",
          std::string("4 error(s)")}) {
        EXPECT_NE(result.output.find(expected), std::string::npos) << expected << "\n"
                                                                   << result.output;
    }
}

TEST(CheckCommand, RefusesAConfigurationThatIsADirectory) {
    TempDir dir;
    const auto result = run_command({gateway_binary(), "check", "-c", dir.path()}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find(dir.path() +
                                 ": error: the configuration is not a regular file (a directory)"),
              std::string::npos)
        << result.output;
}

TEST(CheckCommand, RefusesTopicsTooLongControlCharactersAndSetLevelsWithLineAndColumn) {
    TempDir dir;
    const std::string long_name(65600, 'L');
    const auto path = dir.write("names.yaml",
                                "exchanges:\n"
                                "  - name: ex\n"
                                "    topic: area/set\n"
                                "    producer_id: 10.0.0.1\n"
                                "    exchange_id: 1\n"
                                "    length: 8\n"
                                "    tags:\n"
                                "      - { name: \"A\\0x\", address: 0, type: int }\n"
                                "      - { name: " +
                                    long_name + ", address: 2, type: int }\n");
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    for (const std::string& expected :
         {path +
              ":3:5: error: exchange 'ex' topic 'area/set' has a level 'set', reserved for writes",
          path + ":8:11: error: tag name 'A\\x00x' contains a NUL character of exchange 'ex'",
          path + ":9:11: error: tag 'LLLL",
          std::string("(65600 bytes) of exchange 'ex' makes topic "
                      "'{base_topic}/{topic}/{tag}/set/result' "
                      "65629 bytes long (MQTT allows 65535)")}) {
        EXPECT_NE(result.output.find(expected), std::string::npos) << expected << "\n"
                                                                   << result.output.substr(0, 2000);
    }
}

TEST(CheckCommand, ReportsAPointListFieldRunningOntoTheNextLineAtItsQuote) {
    TempDir dir;
    const auto csv = dir.write("p.csv",
                               "TagName,Node,Address,DataType,AccessType\n"
                               "OK,ex,0.0,Word,Read\n"
                               "\"TAG\nX\",ex,2.0,Word,Read\n");
    const auto path =
        dir.write("p.yaml",
                  "exchanges:\n"
                  "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, points: p.csv }\n");
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find(csv + ":3:1: error: a quoted field runs past the end of the line, "
                                       "to line 4 (newlines inside fields are not supported)\n1 "
                                       "error(s)"),
              std::string::npos)
        << result.output;
}

// A consumed exchange without update timeout is valid, with a warning: without producer
// timestamps nothing would resynchronise it after its producer restarts.
TEST(CheckCommand, WarnsAboutAConsumedExchangeWithoutTimeout) {
    TempDir dir;
    const auto path = dir.write("plc.yaml", R"(gateway:
  id: gw
mqtt:
  url: tcp://127.0.0.1:1
  base_topic: test
exchanges:
  - name: plc
    direction: consume
    producer_id: 10.0.0.7
    exchange_id: 2
    length: 4
    period_ms: 100
    timeout_ms: 0
    tags:
      - { name: COUNTER, address: "0.0", type: dint }
  - name: kept
    direction: consume
    producer_id: 10.0.0.7
    exchange_id: 3
    length: 4
    period_ms: 100
    tags:
      - { name: COUNTER, address: "0.0", type: dint }
)");
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 0) << result.output;
    const auto warning = result.output.find("  warning: timeout_ms is 0");
    ASSERT_NE(warning, std::string::npos) << result.output;
    EXPECT_LT(result.output.find("exchange plc:"), warning) << result.output;
    EXPECT_GT(result.output.find("exchange kept:"), warning) << result.output;
    EXPECT_EQ(warning, result.output.rfind("warning:") - 2) << "one warning only\n"
                                                            << result.output;
}

TEST(CheckCommand, WarnsAboutPlaceholdersAssumedLengthsCaseTwinsAndDotsFor311) {
    TempDir dir;
    const auto path = dir.write("imported.yaml", R"(gateway:
  id: gw
mqtt:
  url: tcp://127.0.0.1:1
  version: 3
  base_topic: acme/site.1
exchanges:
  - name: plc
    direction: consume
    producer_id: 0.0.0.0         # PLACEHOLDER: the producer's id, e.g. its IP
    exchange_id: 2
    period_ms: 100               # PLACEHOLDER: the producer's period
    tags:
      - { name: SPEED, address: "0.0", type: int }
      - { name: speed, address: "2.0", type: int }
)");
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 0) << result.output;
    const auto& out = result.output;
    EXPECT_NE(out.find(path + ":10:5: warning: producer_id is still a placeholder"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find(path + ":12:5: warning: period_ms is still a placeholder"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("warning: length is not set: assumed 4 bytes"), std::string::npos) << out;
    EXPECT_NE(out.find("warning: tags SPEED and speed differ only in case"), std::string::npos)
        << out;
    EXPECT_NE(out.find("warning: topic acme/site.1/plc has dots"), std::string::npos) << out;
}

TEST(RunCommand, RefusesToStartOnAnInvalidConfiguration) {
    TempDir dir;
    const auto path = dir.write("bad.yaml", bad_config);
    const auto result = run_command({gateway_binary(), "run", "-c", path}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find("colour"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("not starting"), std::string::npos) << result.output;
}

TEST(CheckCommand, ExampleConfigurationIsValidAndShowsItsLayout) {
    const std::string path = std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml";
    const auto result = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(result.status, 0) << result.output;
    EXPECT_NE(result.output.find("PRESSAO"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("acme/demo/turbine1/PRESSAO"), std::string::npos) << result.output;
}

TEST(CheckCommand, NamesARawNulByteAndABidirectionalOverrideAtTheirLineAndColumn) {
    // A raw NUL was reported as a bad hex number further on; an RLO (U+202E) passed in a topic,
    // where "area/<RLO>tes/1t" reads "area/t1/set".
    TempDir dir;
    const auto nul =
        dir.write("nul.yaml", std::string("exchanges:\n  - name: ex\n    topic: a") + '\0' +
                                  "b\n    producer_id: 10.0.0.1\n    exchange_id: 1\n    tags:\n"
                                  "      - { name: \"A\\x00\", address: \"0.0\", type: dint }\n");
    auto result = run_command({gateway_binary(), "check", "-c", nul}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find(nul + ":3:13: error: YAML syntax error: a NUL byte (\\x00)"),
              std::string::npos)
        << result.output;
    const auto rlo = dir.write("rlo.yaml",
                               "exchanges:\n  - name: ex\n    topic: area/\xE2\x80\xAEtes/1t\n"
                               "    producer_id: 10.0.0.1\n    exchange_id: 1\n    tags:\n"
                               "      - { name: \"A\\x00\", address: \"0.0\", type: dint }\n");
    result = run_command({gateway_binary(), "check", "-c", rlo}, 10s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find(rlo + ":3:5: error: exchange 'ex' topic 'area/\\u202Etes/1t' "
                                       "contains a bidirectional control character"),
              std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("tag name 'A\\x00' contains a NUL character"), std::string::npos)
        << result.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
