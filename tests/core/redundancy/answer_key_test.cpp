// The key both units of a pair give a write's answer: FNV-1a over the response topic, a NUL and
// the correlation data, the same on every build and machine.

#include "eip2mqtt/core/redundancy/answer_key.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

TEST(AnswerKey, IsFnv1aOfTheTopicANulAndTheCorrelationData) {
    // FNV-1a 64 of "answers/chaos\0w1", computed apart from this code.
    EXPECT_EQ(answer_key("answers/chaos", "w1"), 0x7c1b93a9d3b97bc9ULL);
}

TEST(AnswerKey, TellsTheTopicFromTheCorrelationData) {
    EXPECT_NE(answer_key("ab", ""), answer_key("a", "b"));
    EXPECT_NE(answer_key("a", ""), answer_key("", "a"));
    EXPECT_EQ(answer_key("a/b", "x"), answer_key("a/b", "x"));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
