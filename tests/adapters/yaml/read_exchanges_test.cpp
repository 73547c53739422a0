// The loader's exchanges (read_exchanges.cpp): their keys, their tags and point lists.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>
#include <string>

#include "tests/adapters/yaml/loading.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

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
    EXPECT_EQ(d[0].message, "tag name 'A\\x00B' contains a NUL character of exchange 'ex'");
    EXPECT_EQ(d[1].message, "tag name 'A\\x00C' contains a NUL character of exchange 'ex'");
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

TEST(LoadConfig, AnUnknownTypeSuggestsOursAndListsTheAliases) {
    const auto d =
        bad("exchanges:\n"
            "  - name: ex\n"
            "    producer_id: 10.0.0.1\n"
            "    exchange_id: 1\n"
            "    length: 8\n"
            "    tags:\n"
            "      - { name: T, address: 0, type: float }\n");
    ASSERT_EQ(d.size(), 1u) << dump(d);
    EXPECT_EQ(d[0].mark.line, 7);
    EXPECT_NE(d[0].message.find("unknown type 'float' (did you mean 'real'?)"), std::string::npos)
        << d[0].message;
    for (const char* alias : {"bool", "uint", "dword", "long"}) {
        EXPECT_NE(d[0].message.find(alias), std::string::npos) << alias << ": " << d[0].message;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
