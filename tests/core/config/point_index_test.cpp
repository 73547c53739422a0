#include "eip2mqtt/core/config/point_index.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

std::vector<std::size_t> rows(const PointIndex& index, std::string_view node) {
    const auto span = index.rows_of(node);
    return {span.begin(), span.end()};
}

TEST(PointIndex, GroupsRowsByNodeInFileOrder) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,ex1,0.0,Bit,Read\n"
        "B,ex2,1.0,Word,Read\n"
        "C,ex1,2.0,Word,Read\n"
        "D,ex1,4.0,Real,Read\n",
        "p.csv");
    ASSERT_EQ(list.rows.size(), 4u);
    const PointIndex index(list);
    EXPECT_EQ(rows(index, "ex1"), (std::vector<std::size_t>{0, 2, 3}));
    EXPECT_EQ(rows(index, "ex2"), (std::vector<std::size_t>{1}));
}

TEST(PointIndex, UnknownNodeHasNoRows) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,ex1,0.0,Bit,Read\n",
        "p.csv");
    const PointIndex index(list);
    EXPECT_TRUE(index.rows_of("ex2").empty());
    EXPECT_TRUE(index.rows_of("EX1").empty());  // Node names are case-sensitive, as exchange names
    EXPECT_TRUE(index.rows_of("").empty());
}

TEST(PointIndex, RowsLeftOutForErrorsAreNotIndexed) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,ex1,0.9,Bit,Read\n"
        "B,ex1,1.0,Word,Read\n",
        "p.csv");
    ASSERT_EQ(list.rows.size(), 1u);
    const PointIndex index(list);
    EXPECT_EQ(rows(index, "ex1"), (std::vector<std::size_t>{0}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
