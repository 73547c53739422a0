// Sparkplug B payloads: each EGD type maps to its Sparkplug datatype, what we encode
// is read back by Eclipse Tahu's own decoder (an implementation we did not write), commands are
// read by datatype, and hostile bytes give an error, never a crash.

#include "eip2mqtt/adapters/sparkplug/payload.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "sparkplug_b.pb.h"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::adapters::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;

TEST(SparkplugDatatype, EachEgdTypeHasTheDatatypeTheIssueNames) {
    EXPECT_EQ(datatype_of(TagType::bit), DataType::boolean);
    EXPECT_EQ(datatype_of(TagType::byte), DataType::uint8);
    EXPECT_EQ(datatype_of(TagType::int_), DataType::int16);
    EXPECT_EQ(datatype_of(TagType::word), DataType::uint16);
    EXPECT_EQ(datatype_of(TagType::dint), DataType::int32);
    EXPECT_EQ(datatype_of(TagType::udint), DataType::uint32);
    EXPECT_EQ(datatype_of(TagType::lint), DataType::int64);
    EXPECT_EQ(datatype_of(TagType::real), DataType::float32);
    EXPECT_EQ(datatype_of(TagType::lreal), DataType::float64);
}

Metric metric(std::string name, std::uint64_t alias, DataType type, Value value) {
    Metric m;
    m.name = std::move(name);
    m.alias = alias;
    m.timestamp_ms = 1700000000123;
    m.datatype = type;
    m.value = value;
    return m;
}

/// One metric of every datatype we publish, at values that test their encoding's edges.
Payload every_type() {
    Payload p;
    p.timestamp_ms = 1700000000456;
    p.seq = 255;
    p.metrics = {
        metric("RUN", 1, DataType::boolean, Value{true}),
        metric("MODE", 2, DataType::uint8, Value{std::uint64_t{255}}),
        metric("PRESSURE", 3, DataType::int16, Value{std::int64_t{-32768}}),
        metric("COUNT", 4, DataType::uint16, Value{std::uint64_t{65535}}),
        metric("FLOW", 5, DataType::int32, Value{std::int64_t{-100000}}),
        metric("ENERGY", 6, DataType::uint32, Value{std::uint64_t{4000000000}}),
        metric("TOTAL", 7, DataType::int64, Value{std::int64_t{-2}}),
        metric("TEMP", 8, DataType::float32, Value{1.5f}),
        metric("PRECISE", 9, DataType::float64, Value{0.1}),
    };
    Property unit{"engUnit", DataType::string, std::string("bar")};
    Property writable{"writable", DataType::boolean, Value{false}};
    Property max{"max", DataType::int16, Value{std::int64_t{-7}}};
    p.metrics[2].properties = {unit, writable, max};
    Metric null_metric = metric("UNKNOWN", 10, DataType::int32, Value{std::int64_t{0}});
    null_metric.value.reset();
    null_metric.historical = true;
    p.metrics.push_back(null_metric);
    return p;
}

TEST(SparkplugPayload, TahuReadsEveryDatatypeAsWritten) {
    const auto tahu = test::tahu_decode(encode(every_type()));
    EXPECT_EQ(tahu["timestamp"], "1700000000456");
    EXPECT_EQ(tahu["seq"], "255");
    const auto& m = tahu["metrics"];
    ASSERT_EQ(m.size(), 10u);
    const std::vector<std::pair<std::string, std::string>> types = {
        {"RUN", "Boolean"},    {"MODE", "UInt8"},    {"PRESSURE", "Int16"}, {"COUNT", "UInt16"},
        {"FLOW", "Int32"},     {"ENERGY", "UInt32"}, {"TOTAL", "Int64"},    {"TEMP", "Float"},
        {"PRECISE", "Double"}, {"UNKNOWN", "Int32"}};
    for (std::size_t i = 0; i < types.size(); ++i) {
        EXPECT_EQ(m[i]["name"], types[i].first);
        EXPECT_EQ(m[i]["type"], types[i].second) << m[i];
        EXPECT_EQ(m[i]["alias"], std::to_string(i + 1));
        EXPECT_EQ(m[i]["timestamp"], "1700000000123");
    }
    EXPECT_EQ(m[0]["value"], true);
    EXPECT_EQ(m[1]["value"], 255);
    EXPECT_EQ(m[2]["value"], -32768);
    EXPECT_EQ(m[3]["value"], 65535);
    EXPECT_EQ(m[4]["value"], -100000);
    EXPECT_EQ(m[5]["value"], 4000000000u);
    EXPECT_EQ(m[6]["value"], "-2");  // a Long: Int64 keeps its sign
    EXPECT_EQ(m[7]["value"], 1.5);
    EXPECT_EQ(m[8]["value"], 0.1);
    EXPECT_TRUE(m[9]["value"].is_null());  // is_null
    EXPECT_EQ(m[9]["isHistorical"], true);
    const auto& properties = m[2]["properties"];
    EXPECT_EQ(properties["engUnit"]["type"], "String");
    EXPECT_EQ(properties["engUnit"]["value"], "bar");
    EXPECT_EQ(properties["writable"]["value"], false);
    EXPECT_EQ(properties["max"]["type"], "Int16");
    EXPECT_EQ(properties["max"]["value"], -7);
}

TEST(SparkplugPayload, TahuReadsNoValueFromADataMetricWithoutItsDatatype) {
    // Why DDATA and NDATA keep each metric's datatype, which Sparkplug B 3.0 recommends leaving
    // out (docs/sparkplug.md, "Conformance"): Tahu's decoder, and the hosts built on it, read a
    // value by the datatype it comes with, and find none without it.
    org::eclipse::tahu::protobuf::Payload proto;
    proto.set_timestamp(1700000000000);
    proto.set_seq(1);
    auto& typed = *proto.add_metrics();
    typed.set_alias(3);
    typed.set_datatype(static_cast<std::uint32_t>(DataType::int32));
    typed.set_int_value(42);
    auto& untyped = *proto.add_metrics();
    untyped.set_alias(4);
    untyped.set_int_value(42);
    const auto tahu = test::tahu_decode(proto.SerializeAsString());
    ASSERT_EQ(tahu["metrics"].size(), 2u);
    EXPECT_EQ(tahu["metrics"][0]["value"], 42);
    const auto& untyped_read = tahu["metrics"][1];
    EXPECT_TRUE(!untyped_read.contains("value") || untyped_read["value"].is_null()) << untyped_read;
}

TEST(SparkplugCommand, MetricsAreReadByTheirDatatypeWithNameOrAlias) {
    Payload command;
    command.metrics = {metric("PRESSURE", 3, DataType::int16, Value{std::int64_t{-5}}),
                       metric("", 6, DataType::uint32, Value{std::uint64_t{4000000000}}),
                       metric("TOTAL", 7, DataType::int64, Value{std::int64_t{-2}}),
                       metric("TEMP", 8, DataType::float32, Value{2.5f})};
    const auto decoded = decode_command(encode(command));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    const auto& metrics = decoded.value();
    ASSERT_EQ(metrics.size(), 4u);
    EXPECT_EQ(metrics[0].name, "PRESSURE");
    EXPECT_TRUE(core::plan::same_value(*metrics[0].value, Value{std::int64_t{-5}}));
    EXPECT_TRUE(metrics[1].name.empty());
    EXPECT_EQ(metrics[1].alias, 6u);
    EXPECT_TRUE(core::plan::same_value(*metrics[1].value, Value{std::uint64_t{4000000000}}));
    EXPECT_TRUE(core::plan::same_value(*metrics[2].value, Value{std::int64_t{-2}}));
    EXPECT_TRUE(core::plan::same_value(*metrics[3].value, Value{2.5f}));
}

TEST(SparkplugCommand, AValueOfAnotherKindThanItsDatatypeSaysIsNoValue) {
    org::eclipse::tahu::protobuf::Payload proto;
    auto& m = *proto.add_metrics();
    m.set_name("PRESSURE");
    m.set_datatype(static_cast<std::uint32_t>(DataType::int16));
    m.set_string_value("12");
    auto& unknown_type = *proto.add_metrics();
    unknown_type.set_name("BLOB");
    unknown_type.set_datatype(17);  // Bytes
    unknown_type.set_bytes_value("x");
    const auto decoded = decode_command(proto.SerializeAsString());
    ASSERT_TRUE(decoded.ok());
    EXPECT_FALSE(decoded.value()[0].value.has_value());
    EXPECT_FALSE(decoded.value()[1].datatype.has_value());
    EXPECT_FALSE(decoded.value()[1].value.has_value());
}

TEST(SparkplugCommand, AMetricWithoutADatatypeIsReadAsTheDatatypeItIsGiven) {
    // Sparkplug B 3.0 recommends commands without datatypes: the birth said them.
    org::eclipse::tahu::protobuf::Payload proto;
    proto.add_metrics()->set_int_value(0xFFFFFFFB);  // -5 as an Int8, Int16 or Int32
    proto.add_metrics()->set_long_value(5000000000);
    proto.add_metrics()->set_boolean_value(true);
    auto& null = *proto.add_metrics();
    null.set_is_null(true);
    null.set_double_value(1.0);
    const auto decoded = decode_command(proto.SerializeAsString());
    ASSERT_TRUE(decoded.ok());
    const auto& metrics = decoded.value();
    ASSERT_EQ(metrics.size(), 4u);
    for (const auto& metric : metrics) {
        EXPECT_FALSE(metric.datatype.has_value());
        EXPECT_FALSE(metric.value.has_value());  // nothing says what it is yet
    }
    EXPECT_TRUE(
        core::plan::same_value(*metrics[0].value_as(DataType::int16), Value{std::int64_t{-5}}));
    EXPECT_TRUE(core::plan::same_value(*metrics[0].value_as(DataType::uint32),
                                       Value{std::uint64_t{0xFFFFFFFB}}));
    EXPECT_TRUE(core::plan::same_value(*metrics[1].value_as(DataType::uint64),
                                       Value{std::uint64_t{5000000000}}));
    EXPECT_FALSE(metrics[1].value_as(DataType::uint32).has_value());   // over its range
    EXPECT_FALSE(metrics[1].value_as(DataType::float32).has_value());  // another kind
    EXPECT_TRUE(core::plan::same_value(*metrics[2].value_as(DataType::boolean), Value{true}));
    EXPECT_FALSE(metrics[3].value_as(DataType::float64).has_value());  // is_null
}

TEST(SparkplugCommand, HostileBytesAreAnErrorNotACrash) {
    EXPECT_FALSE(decode_command("\xff\xff\xff\xff\xff").ok());
    EXPECT_FALSE(decode_command(std::string("\x12\x05\x0a\x03", 4)).ok());  // truncated metric
    EXPECT_FALSE(decode_command(std::string(2 << 20, '\0')).ok());          // over the limit
    EXPECT_TRUE(decode_command("").ok());  // an empty payload: no metric
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::sparkplug
