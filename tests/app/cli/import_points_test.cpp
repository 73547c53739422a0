#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/placeholders.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using core::plan::Direction;
using core::plan::TagType;

const std::string section6 = std::string(EIP2MQTT_TEST_DATA) + "/configs/section6.csv";

struct Output {
    int status = 0;
    std::string out;
    std::string err;
};

Output import(const std::string& path) {
    std::ostringstream out;
    std::ostringstream err;
    const int status = run_import_points(path, out, err);
    return {status, out.str(), err.str()};
}

/// A CSV file in the temporary directory, removed afterwards.
class CsvFile {
public:
    explicit CsvFile(const std::string& text) {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ =
            (fs::temp_directory_path() / ("eip2mqtt_import_" + std::string(info->name()) + ".csv"))
                .string();
        std::ofstream(path_) << text;
    }
    ~CsvFile() { std::remove(path_.c_str()); }
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

const core::config::ExchangeConfig* find(const core::config::Config& config,
                                         const std::string& name) {
    for (const auto& exchange : config.exchanges) {
        if (exchange.spec.name == name) return &exchange;
    }
    return nullptr;
}

const core::config::TagConfig* find_tag(const core::config::ExchangeConfig& exchange,
                                        const std::string& name) {
    for (const auto& tag : exchange.tags) {
        if (tag.spec.name == name) return &tag;
    }
    return nullptr;
}

TEST(ImportPoints, Section6OutputIsAValidConfiguration) {
    const auto result = import(section6);
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.err, "");

    const auto config = adapters::yaml::load_config_text(result.out, "imported.yaml");
    ASSERT_TRUE(config.ok()) << result.out << "\n"
                             << (config.ok() ? "" : config.error().front().to_string());
    ASSERT_EQ(config->exchanges.size(), 2u);

    const auto* exchange = find(*config, "Exchange2");
    ASSERT_NE(exchange, nullptr);
    EXPECT_EQ(&config->exchanges[0], exchange);  // first appearance first
    EXPECT_EQ(exchange->spec.direction, Direction::consume);
    EXPECT_EQ(exchange->spec.exchange_id, 1u);
    EXPECT_EQ(exchange->spec.length, 372);
    EXPECT_EQ(exchange->spec.period.count(), 100);
    EXPECT_EQ(exchange->spec.topic, "exchange2");
    ASSERT_EQ(exchange->tags.size(), 9u);
    EXPECT_EQ(exchange->tags[0].spec.name, "TAG1");
    EXPECT_EQ(exchange->tags[8].spec.name, "DENSIDADE_CPO");

    const auto* pressao = find_tag(*exchange, "PRESSAO");
    ASSERT_NE(pressao, nullptr);
    EXPECT_EQ(pressao->spec.address.byte, 126);
    EXPECT_EQ(pressao->spec.address.bit, 0);
    EXPECT_EQ(pressao->spec.type, TagType::int_);  // §6 Word is a 16-bit int
    EXPECT_FALSE(pressao->spec.writable);

    const auto* densidade = find_tag(*exchange, "DENSIDADE_CPO");
    ASSERT_NE(densidade, nullptr);
    EXPECT_EQ(densidade->spec.address.byte, 368);
    EXPECT_EQ(densidade->spec.type, TagType::real);

    const auto* pressao_ok = find_tag(*exchange, "PRESSAO_OK");
    ASSERT_NE(pressao_ok, nullptr);
    EXPECT_EQ(pressao_ok->spec.address.byte, 120);
    EXPECT_EQ(pressao_ok->spec.address.bit, 7);
    EXPECT_EQ(pressao_ok->spec.type, TagType::bit);

    const auto* setpoints = find(*config, "setpoints");
    ASSERT_NE(setpoints, nullptr);
    EXPECT_EQ(setpoints->spec.direction, Direction::produce);
    EXPECT_EQ(setpoints->spec.exchange_id, 2u);
    EXPECT_EQ(setpoints->spec.destination, "127.0.0.1");
    EXPECT_EQ(setpoints->spec.length, 4);
    ASSERT_EQ(setpoints->tags.size(), 1u);
    EXPECT_TRUE(setpoints->tags[0].spec.writable);
    EXPECT_EQ(setpoints->tags[0].spec.type, TagType::real);
}

TEST(ImportPoints, PlaceholdersAreMarked) {
    const auto result = import(section6);
    ASSERT_EQ(result.status, 0);
    EXPECT_NE(result.out.find(R"(- { name: PRESSAO, address: "126.0", type: int })"),
              std::string::npos)
        << result.out;
    EXPECT_NE(
        result.out.find(R"(- { name: SPEED_SP, address: "0.0", type: real, writable: true })"),
        std::string::npos)
        << result.out;
    // Every value the list cannot give is marked, for `check` to warn about.
    std::vector<std::string> keys;
    for (const auto& placeholder : core::config::find_placeholders(result.out, "out.yaml")) {
        keys.push_back(placeholder.key);
    }
    const std::vector<std::string> expected{
        "producer_id", "exchange_id", "length",      "period_ms",  // the consumed exchange
        "producer_id", "exchange_id", "destination", "length",    "period_ms"};  // the produced
    EXPECT_EQ(keys, expected) << result.out;
}

TEST(ImportPoints, AccessTypesOfRealListsAndTopicsWithoutDots) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,Unit.1,0.0,Word,ReadWrite\n"
        "B,Unit.1,2.0,Word,RW\n"
        "C,Unit.2,0.0,Word,R\n");
    const auto result = import(csv.path());
    ASSERT_EQ(result.status, 0) << result.err;
    const auto config = adapters::yaml::load_config_text(result.out, "out.yaml");
    ASSERT_TRUE(config.ok());
    const auto* written = find(config.value(), "Unit.1");
    ASSERT_NE(written, nullptr) << result.out;
    EXPECT_EQ(written->spec.direction, Direction::produce);
    EXPECT_EQ(written->spec.topic, "unit-1");
    EXPECT_TRUE(written->tags[1].spec.writable);
    const auto* read = find(config.value(), "Unit.2");
    ASSERT_NE(read, nullptr) << result.out;
    EXPECT_EQ(read->spec.direction, Direction::consume);
    EXPECT_EQ(read->spec.topic, "unit-2");
}

TEST(ImportPoints, CountAndLengthColumnsBecomeArraysAndStrings) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType,Count,Length\n"
        "TEMPS,Unit,0.0,Real,R,4,\n"
        "BATCH,Unit,16.0,String,R,,12\n"
        "SPEED,Unit,28.0,Real,R,,\n");
    const auto result = import(csv.path());
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_NE(result.out.find("type: real, count: 4"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("type: string, length: 12"), std::string::npos) << result.out;
    const auto config = adapters::yaml::load_config_text(result.out, "out.yaml");
    ASSERT_TRUE(config.ok()) << result.out;
    const auto* unit = find(config.value(), "Unit");
    ASSERT_NE(unit, nullptr) << result.out;
    EXPECT_EQ(find_tag(*unit, "TEMPS")->spec.count, 4);
    EXPECT_EQ(find_tag(*unit, "BATCH")->spec.count, 12);
    EXPECT_EQ(find_tag(*unit, "SPEED")->spec.count, 1);
}

TEST(ImportPoints, MixedReadAndWriteIsAnError) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,Plc,0.0,Word,Read\n"
        "B,Plc,2.0,Word,Write\n");
    const auto result = import(csv.path());
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(result.out, "");
    EXPECT_NE(result.err.find(csv.path() + ":3: error: node Plc mixes Write rows with Read rows"),
              std::string::npos)
        << result.err;
}

TEST(ImportPoints, BadRowsAreReportedWithTheirLine) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,Plc,0.0,Word,Read\n"
        "B,Plc,abc,Word,Read\n");
    const auto result = import(csv.path());
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(result.out, "");
    EXPECT_NE(result.err.find(csv.path() + ":3:"), std::string::npos) << result.err;
}

TEST(ImportPoints, RowsThatMakeNoValidExchangeFailCheckButArePrinted) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,Plc,0.0,Real,Read\n"
        "B,Plc,1399.0,Word,Read\n");
    const auto result = import(csv.path());
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.out.find("name: Plc"), std::string::npos);
    EXPECT_NE(result.err.find("length 1401 is outside 1..1400"), std::string::npos) << result.err;
}

TEST(ImportPoints, AwkwardNamesAreQuoted) {
    const CsvFile csv(
        "TagName,Node,Address,DataType,AccessType\n"
        "\"A: B\",Plc,0.0,Word,Read\n"
        "true,Plc,2.0,Word,Read\n"
        "123,Plc,4.0,Word,Read\n");
    const auto result = import(csv.path());
    ASSERT_EQ(result.status, 0) << result.err;
    const auto config = adapters::yaml::load_config_text(result.out, "imported.yaml");
    ASSERT_TRUE(config.ok()) << result.out;
    const auto& tags = config->exchanges.at(0).tags;
    ASSERT_EQ(tags.size(), 3u);
    EXPECT_EQ(tags[0].spec.name, "A: B");
    EXPECT_EQ(tags[1].spec.name, "true");
    EXPECT_EQ(tags[2].spec.name, "123");
}

TEST(ImportPoints, MissingFileIsAnError) {
    const auto result = import("/nonexistent/points.csv");
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("/nonexistent/points.csv: error: cannot read"), std::string::npos);
}

TEST(ImportPoints, EmptyListIsAnError) {
    const CsvFile csv("TagName,Node,Address,DataType,AccessType\n");
    const auto result = import(csv.path());
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("no points"), std::string::npos) << result.err;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
