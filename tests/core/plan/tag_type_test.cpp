#include "eip2mqtt/core/plan/tag_type.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

constexpr std::array all_types{TagType::bit,  TagType::byte, TagType::int_,
                               TagType::word, TagType::dint, TagType::udint,
                               TagType::real, TagType::lint, TagType::lreal};

TEST(DataTypes, YamlNamesAndAliases) {
    const auto yaml = [](std::string_view name) { return parse_tag_type(name, TypeNaming::yaml); };
    EXPECT_EQ(yaml("bit"), TagType::bit);
    EXPECT_EQ(yaml("bool"), TagType::bit);
    EXPECT_EQ(yaml("byte"), TagType::byte);
    EXPECT_EQ(yaml("usint"), TagType::byte);
    EXPECT_EQ(yaml("int"), TagType::int_);
    EXPECT_EQ(yaml("word"), TagType::word);
    EXPECT_EQ(yaml("uint"), TagType::word);
    EXPECT_EQ(yaml("dint"), TagType::dint);
    EXPECT_EQ(yaml("udint"), TagType::udint);
    EXPECT_EQ(yaml("dword"), TagType::udint);
    EXPECT_EQ(yaml("real"), TagType::real);
    EXPECT_EQ(yaml("lint"), TagType::lint);
    EXPECT_EQ(yaml("long"), TagType::lint);
    EXPECT_EQ(yaml("lreal"), TagType::lreal);
}

TEST(DataTypes, NamesAreCaseInsensitive) {
    EXPECT_EQ(parse_tag_type("REAL", TypeNaming::yaml), TagType::real);
    EXPECT_EQ(parse_tag_type("LReal", TypeNaming::yaml), TagType::lreal);
    EXPECT_EQ(parse_tag_type("WORD", TypeNaming::yaml), TagType::word);
}

TEST(PointLists, OlderNamesReadAsBitIntRealLint) {
    // docs/protocol.md §3 and §6: Bit, Word, Real, Long are bit, int, real, lint.
    const auto csv = [](std::string_view name) {
        return parse_tag_type(name, TypeNaming::point_list);
    };
    EXPECT_EQ(csv("Bit"), TagType::bit);
    EXPECT_EQ(csv("Word"), TagType::int_);
    EXPECT_EQ(csv("WORD"), TagType::int_);
    EXPECT_EQ(csv("word"), TagType::int_);
    EXPECT_EQ(csv("Real"), TagType::real);
    EXPECT_EQ(csv("Long"), TagType::lint);
    EXPECT_EQ(csv("udint"), TagType::udint);
    EXPECT_EQ(csv("uint"), TagType::word);
}

TEST(DataTypes, UnknownNamesAreRejected) {
    for (const char* name : {"", "float", "double", "text", " int", "int ", "dint32"}) {
        EXPECT_EQ(parse_tag_type(name, TypeNaming::yaml), std::nullopt) << name;
        EXPECT_EQ(parse_tag_type(name, TypeNaming::point_list), std::nullopt) << name;
    }
}

TEST(DataTypes, CanonicalNamesRoundTrip) {
    EXPECT_EQ(to_string(TagType::int_), "int");
    EXPECT_EQ(to_string(TagType::udint), "udint");
    for (TagType type : all_types) {
        EXPECT_EQ(parse_tag_type(to_string(type), TypeNaming::yaml), type) << to_string(type);
    }
}

TEST(DataTypes, Sizes) {
    EXPECT_EQ(size_of(TagType::bit), 1u);
    EXPECT_EQ(size_of(TagType::byte), 1u);
    EXPECT_EQ(size_of(TagType::int_), 2u);
    EXPECT_EQ(size_of(TagType::word), 2u);
    EXPECT_EQ(size_of(TagType::dint), 4u);
    EXPECT_EQ(size_of(TagType::udint), 4u);
    EXPECT_EQ(size_of(TagType::real), 4u);
    EXPECT_EQ(size_of(TagType::lint), 8u);
    EXPECT_EQ(size_of(TagType::lreal), 8u);
}

TEST(DataTypes, IntegerTypes) {
    EXPECT_FALSE(is_integer(TagType::bit));
    EXPECT_TRUE(is_integer(TagType::byte));
    EXPECT_TRUE(is_integer(TagType::int_));
    EXPECT_TRUE(is_integer(TagType::word));
    EXPECT_TRUE(is_integer(TagType::dint));
    EXPECT_TRUE(is_integer(TagType::udint));
    EXPECT_FALSE(is_integer(TagType::real));
    EXPECT_TRUE(is_integer(TagType::lint));
    EXPECT_FALSE(is_integer(TagType::lreal));
}

TEST(DataTypes, Ranges) {
    // §3 and §7: int is -32768..32767, word is unsigned.
    EXPECT_EQ(type_min(TagType::int_), -32768.0);
    EXPECT_EQ(type_max(TagType::int_), 32767.0);
    EXPECT_EQ(type_min(TagType::word), 0.0);
    EXPECT_EQ(type_max(TagType::word), 65535.0);
    EXPECT_EQ(type_min(TagType::bit), 0.0);
    EXPECT_EQ(type_max(TagType::bit), 1.0);
    EXPECT_EQ(type_max(TagType::byte), 255.0);
    EXPECT_EQ(type_min(TagType::dint), -2147483648.0);
    EXPECT_EQ(type_max(TagType::dint), 2147483647.0);
    EXPECT_EQ(type_min(TagType::udint), 0.0);
    EXPECT_EQ(type_max(TagType::udint), 4294967295.0);
    EXPECT_EQ(type_max(TagType::real), 3.4028234663852886e38);
    EXPECT_EQ(type_min(TagType::real), -3.4028234663852886e38);
    EXPECT_EQ(type_min(TagType::lint), -9223372036854775808.0);
    EXPECT_EQ(type_max(TagType::lint), 9223372036854775808.0);
    EXPECT_EQ(type_max(TagType::lreal), 1.7976931348623157e308);
}

TEST(DataTypes, HintsNameOurTypeForOtherLanguagesNamesAndTypos) {
    EXPECT_EQ(tag_type_hint("float"), "real");
    EXPECT_EQ(tag_type_hint("Float"), "real");
    EXPECT_EQ(tag_type_hint("double"), "lreal");
    EXPECT_EQ(tag_type_hint("int32"), "dint");
    EXPECT_EQ(tag_type_hint("uint16"), "word");
    EXPECT_EQ(tag_type_hint("boolean"), "bit");
    EXPECT_EQ(tag_type_hint("reel"), "real");
    EXPECT_EQ(tag_type_hint("dintt"), "dint");
    EXPECT_EQ(tag_type_hint("string"), std::nullopt);  // no type of ours holds text
    EXPECT_EQ(tag_type_hint("xyz"), std::nullopt);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
