// A point list's optional engineering columns, through parse_point_list.

#include <gtest/gtest.h>

#include "eip2mqtt/core/config/point_list.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

using plan::ScaleKind;
using plan::ScaleRange;

constexpr std::string_view header =
    "TagName,Node,Address,DataType,AccessType,Units,ScaleType,ScaleRawLow,ScaleRawHigh,"
    "ScaleEULow,ScaleEUHigh,Clamp\n";

PointList parse(std::string_view rows) {
    return parse_point_list(std::string(header) + std::string(rows), "points.csv");
}

TEST(PointColumns, RowsCarryUnitsAndTheirScale) {
    const auto list = parse(
        "LEVEL,tank,0.0,Int,Read,%,Linear,0,32000,0,100,true\n"
        "FLOW,tank,2.0,UInt,Read,m3/h,SquareRoot,0,65535,0,500,\n"
        "TEMP,tank,4.0,Real,Read,degC,,,,,,\n"
        "LEFT,tank,8.0,DInt,Read,,,-1000,1000,100,-100,no\n");
    ASSERT_TRUE(list.errors.empty()) << list.errors.front().message;
    ASSERT_EQ(list.rows.size(), 4u);
    const auto& level = list.rows[0].tag;
    EXPECT_EQ(level.unit(), "%");
    ASSERT_TRUE(level.scale());
    EXPECT_EQ(level.scale()->kind, ScaleKind::linear);
    EXPECT_EQ(level.scale()->raw, (ScaleRange{0, 32000}));
    EXPECT_EQ(level.scale()->eu, (ScaleRange{0, 100}));
    EXPECT_TRUE(level.scale()->clamp);
    EXPECT_EQ(list.rows[1].tag.scale()->kind, ScaleKind::square_root);
    EXPECT_FALSE(list.rows[1].tag.scale()->clamp);
    EXPECT_EQ(list.rows[2].tag.unit(), "degC");
    EXPECT_FALSE(list.rows[2].tag.scale());
    // Ranges without a ScaleType: linear.
    EXPECT_EQ(list.rows[3].tag.scale()->kind, ScaleKind::linear);
    EXPECT_EQ(list.rows[3].tag.scale()->eu, (ScaleRange{100, -100}));
}

TEST(PointColumns, AListWithoutThemIsAsBefore) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,ex,0.0,Word,Read\n",
        "points.csv");
    ASSERT_TRUE(list.errors.empty());
    EXPECT_FALSE(list.rows.at(0).tag.scale());
    EXPECT_EQ(list.rows.at(0).tag.unit(), "");
}

TEST(PointColumns, BadFieldsAreRefusedAtTheirColumn) {
    const auto list = parse(
        "A,ex,0.0,Int,Read,,Cubic,0,1,0,1,\n"
        "B,ex,2.0,Int,Read,,Linear,0,x,0,1,\n"
        "C,ex,4.0,Int,Read,,Linear,0,1,,,\n"
        "D,ex,6.0,Int,Read,,,0,1,0,1,maybe\n"
        "E,ex,8.0,Int,Read,,,,,,,\n");
    ASSERT_EQ(list.errors.size(), 4u);
    EXPECT_EQ(list.errors[0].mark.line, 2);
    EXPECT_EQ(list.errors[0].mark.column, 20);  // ScaleType
    EXPECT_NE(list.errors[0].message.find("unknown ScaleType Cubic"), std::string::npos);
    EXPECT_EQ(list.errors[1].mark.column, 29);  // ScaleRawHigh
    EXPECT_NE(list.errors[1].message.find("expected a number, not x"), std::string::npos);
    EXPECT_EQ(list.errors[2].mark.column, 20);  // the ScaleType of a scale lacking ranges
    EXPECT_NE(list.errors[2].message.find("needs ScaleRawLow"), std::string::npos);
    EXPECT_NE(list.errors[3].message.find("Clamp"), std::string::npos);
    ASSERT_EQ(list.rows.size(), 1u);  // E
    EXPECT_EQ(list.rows[0].tag.name, "E");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
