#include "eip2mqtt/core/redundancy/bd_seq.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

TEST(SessionBdSeq, ANewLeaderTakesOneMoreThanTheLastItHeard) {
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{0}, 0), 1);
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{41}, 0), 42);
    // Whatever its own node would take next: the host must see a session other than the last.
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{41}, 42), 42);
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{41}, 7), 42);
}

TEST(SessionBdSeq, AfterTwoHundredFiftyFiveComesZero) {
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{255}, 3), 0);
    EXPECT_EQ(next_session_bd_seq(std::uint8_t{254}, 3), 255);
}

TEST(SessionBdSeq, HavingHeardNoneItTakesItsOwnNext) {
    EXPECT_EQ(next_session_bd_seq(std::nullopt, 0), 0);
    EXPECT_EQ(next_session_bd_seq(std::nullopt, 9), 9);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
