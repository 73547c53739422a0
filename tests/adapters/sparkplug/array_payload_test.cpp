// Arrays and strings in Sparkplug B 3.0 payloads: each type's array datatype, the elements
// packed little-endian in bytes_value (the specification's examples), a BooleanArray as its
// count and its bits, and a string tag as a String metric that Eclipse Tahu reads.

#include <gtest/gtest.h>

#include <string>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "sparkplug_b.pb.h"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::adapters::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;

/// The bytes_value of a one-metric payload of `type` holding `value`.
std::string array_bytes_of(DataType type, const Value& value) {
    Payload payload;
    Metric metric;
    metric.name = "A";
    metric.datatype = type;
    metric.value = value;
    payload.metrics.push_back(metric);
    org::eclipse::tahu::protobuf::Payload proto;
    EXPECT_TRUE(proto.ParseFromString(encode(payload)));
    EXPECT_EQ(proto.metrics(0).datatype(), static_cast<std::uint32_t>(type));
    return proto.metrics(0).bytes_value();
}

std::string hex(const std::string& bytes) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string out;
    for (const char c : bytes) {
        const auto b = static_cast<unsigned char>(c);
        out += digits[b >> 4];
        out += digits[b & 0xF];
    }
    return out;
}

TEST(SparkplugArrays, EachTypeHasItsArrayDatatype) {
    EXPECT_EQ(datatype_of(TagType::bit, true), DataType::boolean_array);
    EXPECT_EQ(datatype_of(TagType::byte, true), DataType::uint8_array);
    EXPECT_EQ(datatype_of(TagType::int_, true), DataType::int16_array);
    EXPECT_EQ(datatype_of(TagType::word, true), DataType::uint16_array);
    EXPECT_EQ(datatype_of(TagType::dint, true), DataType::int32_array);
    EXPECT_EQ(datatype_of(TagType::udint, true), DataType::uint32_array);
    EXPECT_EQ(datatype_of(TagType::lint, true), DataType::int64_array);
    EXPECT_EQ(datatype_of(TagType::real, true), DataType::float_array);
    EXPECT_EQ(datatype_of(TagType::lreal, true), DataType::double_array);
    EXPECT_EQ(datatype_of(TagType::string), DataType::string);
    EXPECT_EQ(static_cast<int>(DataType::int8_array), 22);
    EXPECT_EQ(static_cast<int>(DataType::boolean_array), 32);
    EXPECT_EQ(element_of(DataType::float_array), DataType::float32);
    EXPECT_EQ(element_of(DataType::float32), std::nullopt);
}

TEST(SparkplugArrays, ElementsArePackedLittleEndian) {
    const auto list = [](auto... v) { return core::plan::make_list({Value{v}...}); };
    EXPECT_EQ(hex(array_bytes_of(DataType::int32_array,
                                 list(std::int64_t{123456789}, std::int64_t{987654321}))),
              "15cd5b07b168de3a");
    EXPECT_EQ(hex(array_bytes_of(DataType::int8_array, list(std::int64_t{-23}, std::int64_t{123}))),
              "e97b");
    EXPECT_EQ(
        hex(array_bytes_of(DataType::uint16_array, list(std::uint64_t{1}, std::uint64_t{65535}))),
        "0100ffff");
    EXPECT_EQ(hex(array_bytes_of(DataType::int64_array, list(std::int64_t{-1}))),
              "ffffffffffffffff");
    EXPECT_EQ(hex(array_bytes_of(DataType::float_array, list(1.0f, -2.0f))), "0000803f000000c0");
    EXPECT_EQ(hex(array_bytes_of(DataType::double_array, list(1.0))), "000000000000f03f");
}

TEST(SparkplugArrays, BooleansAreACountAndTheirBitsFirstHighest) {
    std::vector<Value> bits;
    for (const bool b :
         {false, false, true, true, false, true, false, false, true, true, false, true}) {
        bits.emplace_back(b);
    }
    EXPECT_EQ(hex(array_bytes_of(DataType::boolean_array, core::plan::make_list(bits))),
              "0c00000034d0");
}

TEST(SparkplugStrings, TahuReadsAStringTagsText) {
    Payload payload;
    Metric metric;
    metric.name = "BATCH";
    metric.datatype = DataType::string;
    metric.value = Value{core::plan::make_text("B-\xC3\xA9 17")};
    payload.metrics.push_back(metric);
    const auto tahu = test::tahu_decode(encode(payload));
    EXPECT_EQ(tahu["metrics"][0]["type"], "String");
    EXPECT_EQ(tahu["metrics"][0]["value"], "B-\xC3\xA9 17");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::sparkplug
