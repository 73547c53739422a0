#include "eip2mqtt/app/cli/dissector/field_names.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::app::dissector {
namespace EIP2MQTT_THIS_FILE {

TEST(FieldPart, KeepsWhatWiresharkAcceptsInAFieldName) {
    EXPECT_EQ(field_part("SPEED_SP-2"), "SPEED_SP-2");
    EXPECT_EQ(field_part("turbine1"), "turbine1");
}

TEST(FieldPart, ReplacesSpacesDotsAndOtherPunctuation) {
    EXPECT_EQ(field_part("Pump 1.speed"), "Pump_1_speed");
    EXPECT_EQ(field_part("a/b:c[0]"), "a_b_c_0_");
}

TEST(FieldPart, ReplacesEachMultiByteCharacterByOneUnderscore) {
    EXPECT_EQ(field_part("PRESS\xC3\x83O"), "PRESS_O");       // PRESSÃO
    EXPECT_EQ(field_part("\xE6\xB8\xA9\xE5\xBA\xA6"), "__");  // 温度
    EXPECT_EQ(field_part("\xF0\x9F\x94\xA5hot"), "_hot");     // a 4-byte character
}

TEST(FieldParts, NamesThatEscapeAlikeGetNumberedInOrder) {
    FieldParts parts;
    EXPECT_EQ(parts.unique("a b"), "a_b");
    EXPECT_EQ(parts.unique("a.b"), "a_b_2");
    EXPECT_EQ(parts.unique("a_b"), "a_b_3");
    EXPECT_EQ(parts.unique("c"), "c");
}

TEST(FieldParts, AReservedPartIsNeverHandedOut) {
    FieldParts parts({"expert"});
    EXPECT_EQ(parts.unique("expert"), "expert_2");
}

TEST(FieldParts, AnEmptyNameBecomesAnUnderscore) {
    FieldParts parts;
    EXPECT_EQ(parts.unique(""), "_");
    EXPECT_EQ(parts.unique("\xC3\xA9"), "__2");  // é escapes to "_", which is taken
}

TEST(LuaString, EscapesQuotesBackslashesAndEveryNonAsciiByte) {
    EXPECT_EQ(lua_string("plain"), "\"plain\"");
    EXPECT_EQ(lua_string("say \"hi\" \\o/"), "\"say \\\"hi\\\" \\\\o/\"");
    EXPECT_EQ(lua_string("a\nb"), "\"a\\010b\"");
    EXPECT_EQ(lua_string("\xC3\x83"
                         "1"),
              "\"\\195\\1311\"");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::dissector
