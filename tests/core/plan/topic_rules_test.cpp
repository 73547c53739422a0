#include "eip2mqtt/core/plan/topic_rules.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core::plan {
namespace {

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

}  // namespace
}  // namespace eip2mqtt::core::plan
