#include "eip2mqtt/core/plan/topic_rules.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TEST(TopicRules, PlainAndMultibyteTextIsAccepted) {
    EXPECT_EQ(text_problem("acme/plant 1/PRESSÃO"), "");
    EXPECT_EQ(text_problem("\xE2\x82\xAC \xF0\x9F\x98\x80"), "");  // euro sign, an emoji
    EXPECT_EQ(text_problem(""), "");
}

TEST(TopicRules, NulAndControlCharactersAreRefused) {
    EXPECT_EQ(text_problem(std::string("a\0b", 3)), "contains a NUL character");
    EXPECT_EQ(text_problem("a\nb"), "contains a control character");
    EXPECT_EQ(text_problem("a\x1F"), "contains a control character");
    EXPECT_EQ(text_problem("a\x7F"), "contains a control character");
    EXPECT_EQ(text_problem("\xC2\x85"), "contains a control character");  // U+0085
}

TEST(TopicRules, InvalidUtf8IsRefused) {
    EXPECT_EQ(text_problem("\xFF"), "is not valid UTF-8");
    EXPECT_EQ(text_problem("\xC3"), "is not valid UTF-8");              // cut short
    EXPECT_EQ(text_problem("\xC0\xAF"), "is not valid UTF-8");          // overlong '/'
    EXPECT_EQ(text_problem("\xED\xA0\x80"), "is not valid UTF-8");      // a surrogate
    EXPECT_EQ(text_problem("\xF4\x90\x80\x80"), "is not valid UTF-8");  // past U+10FFFF
    EXPECT_EQ(text_problem("\x80"), "is not valid UTF-8");              // a lone continuation
}

TEST(TopicRules, NonCharactersAreRefused) {
    EXPECT_EQ(text_problem("\xEF\xBF\xBF"), "contains a Unicode non-character");  // U+FFFF
    EXPECT_EQ(text_problem("\xEF\xB7\x90"), "contains a Unicode non-character");  // U+FDD0
}

TEST(TopicRules, BidirectionalControlsAreRefused) {
    // "acme/<RLO>tes/eulav" shows as "acme/value/set" on a terminal or a dashboard.
    const std::string problem =
        "contains a bidirectional control character (text would read other than it is stored)";
    EXPECT_EQ(text_problem("acme/\xE2\x80\xAEtes/eulav"), problem);  // U+202E RLO
    for (const char* control : {"\xD8\x9C", "\xE2\x80\x8E", "\xE2\x80\x8F", "\xE2\x80\xAA",
                                "\xE2\x80\xAD", "\xE2\x81\xA6", "\xE2\x81\xA9"}) {
        EXPECT_EQ(text_problem(std::string("a") + control + "b"), problem) << control;
        EXPECT_EQ(topic_name_problem(std::string("a/") + control), problem) << control;
    }
    // Their neighbours are text: U+200D (zero-width joiner, in emoji), U+202F, U+2065, U+206A.
    for (const char* other :
         {"\xE2\x80\x8D", "\xE2\x80\xAF", "\xE2\x81\xA5", "\xE2\x81\xAA", "\xD8\x9B"}) {
        EXPECT_EQ(text_problem(std::string("a") + other), "") << other;
    }
}

TEST(TopicRules, TopicNamesHaveNoWildcardAndFitTwoBytesOfLength) {
    EXPECT_EQ(topic_name_problem("a/b"), "");
    EXPECT_EQ(topic_name_problem(""), "is empty");
    EXPECT_EQ(topic_name_problem("rt/#"), "contains a wildcard ('+' or '#')");
    EXPECT_EQ(topic_name_problem("a/+/b"), "contains a wildcard ('+' or '#')");
    EXPECT_EQ(topic_name_problem(std::string(max_topic_bytes, 'a')), "");
    EXPECT_EQ(topic_name_problem(std::string(max_topic_bytes + 1, 'a')),
              "is 65536 bytes long (MQTT allows 65535)");
    EXPECT_EQ(topic_name_problem("a\tb"), "contains a control character");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
