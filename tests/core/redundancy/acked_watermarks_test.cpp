#include "eip2mqtt/core/redundancy/acked_watermarks.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

TEST(AckedWatermarks, TheNewestAcknowledgedSampleOfEachExchange) {
    AckedWatermarks marks;
    const auto a1 = marks.published(1, {10});
    const auto b1 = marks.published(2, {500});
    const auto a2 = marks.published(1, {11});
    EXPECT_FALSE(marks.watermark(1).has_value());
    marks.acknowledged(a1);
    EXPECT_EQ(marks.watermark(1), SampleKey{10});
    EXPECT_FALSE(marks.watermark(2).has_value());
    marks.acknowledged(a2);
    marks.acknowledged(b1);
    EXPECT_EQ(marks.watermark(1), SampleKey{11});
    EXPECT_EQ(marks.watermark(2), SampleKey{500});
}

TEST(AckedWatermarks, NewestByPublicationWhateverTheOrderOfAcknowledgements) {
    AckedWatermarks marks;
    const auto first = marks.published(1, {10});
    const auto second = marks.published(1, {11});
    marks.acknowledged(second);
    marks.acknowledged(first);  // sent again after a reconnect, acknowledged late
    EXPECT_EQ(marks.watermark(1), SampleKey{11});
}

TEST(AckedWatermarks, TokensAreItsOwnAndNeverZero) {
    AckedWatermarks marks;
    const auto token = marks.published(1, {10});
    EXPECT_NE(token, 0u);
    EXPECT_TRUE(AckedWatermarks::owns(token));
    EXPECT_FALSE(AckedWatermarks::owns(12345));
    marks.acknowledged(12345);  // a journal entry's: not ours
    marks.acknowledged(AckedWatermarks::token_bit);
    EXPECT_FALSE(marks.watermark(1).has_value());
}

TEST(AckedWatermarks, AnAcknowledgementBeyondWhatIsRememberedIsIgnored) {
    AckedWatermarks marks(2);
    const auto old = marks.published(1, {10});
    marks.published(1, {11});
    marks.published(1, {12});  // takes the slot of the first
    marks.acknowledged(old);
    EXPECT_FALSE(marks.watermark(1).has_value());
}

TEST(AckedWatermarks, ANewLeaderStartsFromTheWatermarkItHeard) {
    AckedWatermarks marks;
    marks.start_at(1, {10});
    EXPECT_EQ(marks.watermark(1), SampleKey{10});
    marks.acknowledged(marks.published(1, {11}));
    EXPECT_EQ(marks.watermark(1), SampleKey{11});
}

TEST(AckedWatermarks, ClearedOrForgottenNothingIsLeft) {
    AckedWatermarks marks;
    const auto pending = marks.published(1, {10});
    marks.acknowledged(marks.published(2, {20}));
    marks.clear();
    marks.acknowledged(pending);
    EXPECT_FALSE(marks.watermark(1).has_value());
    EXPECT_FALSE(marks.watermark(2).has_value());

    const auto forgotten = marks.published(3, {30});
    marks.acknowledged(marks.published(4, {40}));
    marks.forget(3);
    marks.forget(4);
    marks.acknowledged(forgotten);
    EXPECT_FALSE(marks.watermark(3).has_value());
    EXPECT_FALSE(marks.watermark(4).has_value());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
