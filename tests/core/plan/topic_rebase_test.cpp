// How a connection with a base_topic of its own says the plans' topics: the first base swapped
// for its own at the start of a topic, whole levels only, and back.

#include "eip2mqtt/core/plan/topic_rebase.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

std::string out(const TopicRebase& rebase, std::string topic) {
    rebase.outward(topic);
    return topic;
}

std::string in(const TopicRebase& rebase, std::string topic) {
    rebase.inward(topic);
    return topic;
}

TEST(TopicRebase, TheFirstBaseIsSwappedAtTheStart) {
    const TopicRebase rebase("eip2mqtt", "acme/plant1");
    EXPECT_EQ(out(rebase, "eip2mqtt/line/SPEED"), "acme/plant1/line/SPEED");
    EXPECT_EQ(out(rebase, "eip2mqtt/+/set"), "acme/plant1/+/set");
    EXPECT_EQ(out(rebase, "eip2mqtt"), "acme/plant1");
    EXPECT_EQ(in(rebase, "acme/plant1/line/SPEED/set"), "eip2mqtt/line/SPEED/set");
}

TEST(TopicRebase, OnlyWholeLevelsAndOnlyAtTheStart) {
    const TopicRebase rebase("eip2mqtt", "ent");
    EXPECT_EQ(out(rebase, "eip2mqttx/line"), "eip2mqttx/line");
    EXPECT_EQ(out(rebase, "site/eip2mqtt/line"), "site/eip2mqtt/line");
    EXPECT_EQ(in(rebase, "entx/line"), "entx/line");
    EXPECT_EQ(in(rebase, ""), "");
}

TEST(TopicRebase, OneBaseIsIdentity) {
    const TopicRebase rebase("plant", "plant");
    EXPECT_TRUE(rebase.identity());
    EXPECT_TRUE(TopicRebase().identity());
    EXPECT_EQ(out(rebase, "plant/line"), "plant/line");
    EXPECT_FALSE(TopicRebase("a", "b").identity());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
