#include "eip2mqtt/core/config/point_list.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

using plan::Address;
using plan::TagType;

// docs/protocol.md §6, verbatim.
constexpr std::string_view section6 =
    "TagName,Node,Address,DataType,AccessType\n"
    "TAG1,Exchange2,119.5,Bit,Read\n"
    "TAG2,Exchange2,119.6,Bit,Read\n"
    "SISTEMA1OK,Exchange2,120.4,Bit,Read\n"
    "PRESSAO_OK,Exchange2,120.7,Bit,Read\n"
    "PRESSAO,Exchange2,126.0,Word,Read\n"
    "TEMPERATURA,Exchange2,134.0,Word,Read\n"
    "CORRENTE_ELT,Exchange2,166.0,Word,Read\n"
    "TENSAO,Exchange2,208.0,Real,Read\n"
    "DENSIDADE_CPO,Exchange2,368.0,Real,Read\n";

TEST(PointLists, Section6ExampleParses) {
    const auto list = parse_point_list(section6, "points.csv");
    EXPECT_TRUE(list.errors.empty());
    ASSERT_EQ(list.rows.size(), 9u);
    EXPECT_EQ(list.rows[0].tag.name, "TAG1");
    EXPECT_EQ(list.rows[0].node, "Exchange2");
    EXPECT_EQ(list.rows[0].tag.address, (Address{119, 5}));
    EXPECT_EQ(list.rows[0].tag.type, TagType::bit);
    EXPECT_FALSE(list.rows[0].write);
    EXPECT_FALSE(list.rows[0].tag.writable);
    EXPECT_EQ(list.rows[0].mark.file, "points.csv");
    // Every row's mark shares the one file name (a copy per row was 100,000 heap blocks).
    EXPECT_EQ(&list.rows[0].mark.file.str(), &list.rows[7].mark.file.str());
    EXPECT_EQ(list.rows[0].mark.line, 2);
    EXPECT_EQ(list.rows[0].mark.column, 1);
    // §6: Word is a signed 16-bit value in point lists.
    EXPECT_EQ(list.rows[4].tag.name, "PRESSAO");
    EXPECT_EQ(list.rows[4].tag.type, TagType::int_);
    EXPECT_EQ(list.rows[7].tag.type, TagType::real);
    EXPECT_EQ(list.rows[8].tag.address, (Address{368, 0}));
    EXPECT_EQ(list.rows[8].mark.line, 10);
}

TEST(PointLists, LongIsLintAndSection3NamesWork) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,0.0,Long,Read\nB,N,8.0,lreal,Read\nC,N,16.0,UDINT,Read\n",
        "p.csv");
    ASSERT_EQ(list.rows.size(), 3u);
    EXPECT_EQ(list.rows[0].tag.type, TagType::lint);
    EXPECT_EQ(list.rows[1].tag.type, TagType::lreal);
    EXPECT_EQ(list.rows[2].tag.type, TagType::udint);
}

TEST(PointLists, WriteAccessMakesWritableTags) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\nSP,setpoints,0.0,Real,WRITE\n"
        "RD,setpoints,4.0,Real,read\n",
        "p.csv");
    ASSERT_EQ(list.rows.size(), 2u);
    EXPECT_TRUE(list.rows[0].write);
    EXPECT_TRUE(list.rows[0].tag.writable);
    EXPECT_FALSE(list.rows[1].write);
}

TEST(PointLists, ColumnsInAnyOrderAnyCaseWithQuotesCommentsAndCrlf) {
    const auto list = parse_point_list(
        "\"accesstype\" , DATATYPE,address,node,TagName,Comment\r\n"
        "# a comment\r\n"
        "\r\n"
        "Read,Bit,3.2,\"Ex, 2\",\"TAG \"\"X\"\"\",free text\r\n",
        "p.csv");
    EXPECT_TRUE(list.errors.empty()) << list.errors.front().message;
    ASSERT_EQ(list.rows.size(), 1u);
    EXPECT_EQ(list.rows[0].tag.name, "TAG \"X\"");
    EXPECT_EQ(list.rows[0].node, "Ex, 2");
    EXPECT_EQ(list.rows[0].tag.address, (Address{3, 2}));
    EXPECT_EQ(list.rows[0].mark.line, 4);
}

TEST(PointLists, MissingColumnIsAnError) {
    const auto list = parse_point_list("TagName,Node,Address,DataType\nA,N,0.0,Bit\n", "p.csv");
    EXPECT_TRUE(list.rows.empty());
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].mark.line, 1);
    EXPECT_NE(list.errors[0].message.find("accesstype"), std::string::npos);
}

TEST(PointLists, BadRowsAreReportedWithFileAndLineAndGoodRowsKept) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,1.8,Bit,Read\n"    // bit 8
        "B,N,2.0,Float,Read\n"  // unknown type
        "C,N,3.0,Bit,Maybe\n"   // unknown access
        "D,N\n"                 // too few fields
        "E,N,4.0,Bit,Read\n"
        ",N,5.0,Bit,Read\n",  // empty name
        "p.csv");
    ASSERT_EQ(list.rows.size(), 1u);
    EXPECT_EQ(list.rows[0].tag.name, "E");
    ASSERT_EQ(list.errors.size(), 5u);
    EXPECT_EQ(list.errors[0].mark.file, "p.csv");
    EXPECT_EQ(list.errors[0].mark.line, 2);
    EXPECT_EQ(list.errors[0].mark.column, 5);  // the Address field
    EXPECT_EQ(list.errors[1].mark.line, 3);
    EXPECT_NE(list.errors[1].message.find("Float"), std::string::npos);
    // The types are documented in the repository, where a user can read them.
    EXPECT_NE(list.errors[1].message.find("docs/protocol.md section 3, \"Data types\""),
              std::string::npos)
        << list.errors[1].message;
    EXPECT_EQ(list.errors[2].mark.line, 4);
    EXPECT_NE(list.errors[2].message.find("Maybe"), std::string::npos);
    EXPECT_EQ(list.errors[3].mark.line, 5);
    EXPECT_EQ(list.errors[4].mark.line, 7);
}

TEST(PointLists, EmptyTextHasNoHeader) {
    const auto list = parse_point_list("", "p.csv");
    EXPECT_TRUE(list.rows.empty());
    EXPECT_EQ(list.errors.size(), 1u);
}

TEST(PointLists, UnterminatedQuote) {
    const auto list =
        parse_point_list("TagName,Node,Address,DataType,AccessType\n\"A,N,0.0,Bit,Read\n", "p.csv");
    EXPECT_TRUE(list.rows.empty());
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].mark.line, 2);
}

TEST(PointLists, AQuotedFieldAcrossLinesIsOneErrorAndItsOtherLinesAreNoRows) {
    // Without CSV's rule the second line would be a row of its own, a tag named `X"`.
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "\"TAG\nX\",N,0.0,Bit,Read\n"
        "B,N,1.0,Bit,Read\n",
        "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].mark.line, 2);
    EXPECT_EQ(list.errors[0].mark.column, 1);
    EXPECT_EQ(list.errors[0].message,
              "a quoted field runs past the end of the line, to line 3 (newlines inside fields "
              "are not supported)");
    ASSERT_EQ(list.rows.size(), 1u);
    EXPECT_EQ(list.rows[0].tag.name, "B");
    EXPECT_EQ(list.rows[0].mark.line, 4);
}

TEST(PointLists, AQuotedFieldAcrossSeveralLinesWithQuotesAndCrlf) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\r\n"
        "A, \"No\"\"de\r\n"
        "\r\n"
        "two\",0.0,Bit,\"Re\r\n"
        "ad\"\r\n"
        "B,N,1.0,Bit,Read\r\n",
        "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].mark.line, 2);
    EXPECT_EQ(list.errors[0].mark.column, 4);  // the opening quote
    EXPECT_NE(list.errors[0].message.find("to line 5"), std::string::npos)
        << list.errors[0].message;
    ASSERT_EQ(list.rows.size(), 1u);
    EXPECT_EQ(list.rows[0].tag.name, "B");
    EXPECT_EQ(list.rows[0].mark.line, 6);
}

TEST(PointLists, AQuoteThatNeverClosesEndsTheList) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,0.0,Bit,Read\n"
        "\"B,N,1.0,Bit,Read\n"
        "C,N,2.0,Bit,Read\n",
        "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].mark.line, 3);
    EXPECT_EQ(list.errors[0].message,
              "unterminated quoted field (no closing quote before the end of the file)");
    ASSERT_EQ(list.rows.size(), 1u);
    EXPECT_EQ(list.rows[0].tag.name, "A");
}

TEST(PointLists, MessagesShowControlCharactersEscaped) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\nA,N,\x1B[2J,Bit,Read\n", "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_EQ(list.errors[0].message, "bad address '\\x1B[2J' (expected byte.bit)");
}

TEST(PointLists, AccessTypesAsPointListsSpellThem) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,0.0,Bit,R\n"
        "B,N,1.0,Bit,read\n"
        "C,M,2.0,Bit,ReadWrite\n"
        "D,M,3.0,Bit,Read/Write\n"
        "E,M,4.0,Bit,RW\n"
        "F,M,5.0,Bit,W\n"
        "G,M,6.0,Bit,rw\n",
        "p.csv");
    ASSERT_TRUE(list.errors.empty()) << list.errors[0].message;
    ASSERT_EQ(list.rows.size(), 7u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_FALSE(list.rows[i].write) << list.rows[i].tag.name;
        EXPECT_FALSE(list.rows[i].tag.writable) << list.rows[i].tag.name;
    }
    for (std::size_t i = 2; i < 7; ++i) {
        EXPECT_TRUE(list.rows[i].write) << list.rows[i].tag.name;
        EXPECT_TRUE(list.rows[i].tag.writable) << list.rows[i].tag.name;
    }
}

TEST(PointLists, AnUnknownAccessTypeListsTheSpellingsTaken) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,0.0,Bit,Maybe\n",
        "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_NE(list.errors[0].message.find("ReadWrite"), std::string::npos)
        << list.errors[0].message;
}

TEST(PointLists, AFloatDataTypeSuggestsReal) {
    const auto list = parse_point_list(
        "TagName,Node,Address,DataType,AccessType\n"
        "A,N,0.0,Float,Read\n",
        "p.csv");
    ASSERT_EQ(list.errors.size(), 1u);
    EXPECT_NE(list.errors[0].message.find("did you mean 'real'?"), std::string::npos)
        << list.errors[0].message;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
