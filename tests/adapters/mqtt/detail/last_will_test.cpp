// LastWill: the will of the current connection, said once at most.

#include "adapters/mqtt/detail/last_will.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

Message will(std::string topic) {
    Message message;
    message.topic = std::move(topic);
    return message;
}

TEST(LastWill, IsTakenOnce) {
    LastWill last;
    EXPECT_FALSE(last.take());
    last.set(will("a/death"));
    const auto taken = last.take();
    ASSERT_TRUE(taken);
    EXPECT_EQ(taken->topic, "a/death");
    EXPECT_FALSE(last.take());
}

TEST(LastWill, TheNextConnectionsWillReplacesItAndAForgottenOneIsNeverSaid) {
    LastWill last;
    last.set(will("first"));
    last.set(will("second"));
    EXPECT_EQ(last.take()->topic, "second");
    last.set(will("third"));
    last.forget();
    EXPECT_FALSE(last.take());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
