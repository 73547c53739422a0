#include "eip2mqtt/core/quality/quality.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::quality {
namespace EIP2MQTT_THIS_FILE {

using exchange::ConsumeState;

TEST(Quality, Names) {
    EXPECT_EQ(to_string(Quality::good), "good");
    EXPECT_EQ(to_string(Quality::stale), "stale");
    EXPECT_EQ(to_string(Quality::bad), "bad");
}

TEST(Quality, NothingToPublishWhileWaiting) {
    EXPECT_EQ(quality_of(ConsumeState::waiting), std::nullopt);
}

TEST(Quality, GoodWhileReceiving) { EXPECT_EQ(quality_of(ConsumeState::ok), Quality::good); }

TEST(Quality, StaleAfterTimeout) { EXPECT_EQ(quality_of(ConsumeState::stale), Quality::stale); }

TEST(Quality, BadDuringMismatch) {
    EXPECT_EQ(quality_of(ConsumeState::signature_mismatch), Quality::bad);
    EXPECT_EQ(quality_of(ConsumeState::length_mismatch), Quality::bad);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::quality
