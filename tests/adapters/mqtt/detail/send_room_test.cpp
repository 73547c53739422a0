#include "adapters/mqtt/detail/send_room.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(SendRoom, TheWindowFillsToItsLimitThenWaitsForAnEighthOfIt) {
    EXPECT_TRUE(has_room(0, 256, false));
    EXPECT_TRUE(has_room(255, 256, false));
    EXPECT_FALSE(has_room(256, 256, false));
    // Once full: one wake-up per burst of 32.
    EXPECT_FALSE(has_room(225, 256, true));
    EXPECT_TRUE(has_room(224, 256, true));
    // A window too small for an eighth refills one at a time.
    EXPECT_FALSE(has_room(5, 5, true));
    EXPECT_TRUE(has_room(4, 5, true));
    EXPECT_TRUE(has_room(0, 1, true));
    EXPECT_FALSE(has_room(1, 1, false));
}

TEST(SendRoom, TheAcknowledgedWindowUsesTheWholeReceiveMaximumOneSlotAtATime) {
    // Mosquitto's default Receive Maximum: all 20 slots are ours while nothing of the client's
    // own awaits its PUBACK, and each completion frees one at once.
    EXPECT_TRUE(has_acknowledged_room(19, 0, 20));
    EXPECT_FALSE(has_acknowledged_room(20, 0, 20));
}

TEST(SendRoom, TheClientsOwnUnacknowledgedPublicationsTakeSlots) {
    EXPECT_FALSE(has_acknowledged_room(19, 1, 20));  // `online` in flight
    EXPECT_TRUE(has_acknowledged_room(18, 1, 20));
    EXPECT_FALSE(has_acknowledged_room(0, 1, 1));  // a window of one, taken by `offline`
    EXPECT_FALSE(has_acknowledged_room(0, 2, 1));  // never wraps around
}

TEST(SendRoom, ASaturatedConnectionRefillsTwoSlotsAtATime) {
    EXPECT_FALSE(has_saturated_room(19, 0, 20));
    EXPECT_TRUE(has_saturated_room(18, 0, 20));
    EXPECT_FALSE(has_saturated_room(17, 2, 20));  // `online` and `offline` in flight
    // A window of two or fewer still refills one at a time.
    EXPECT_TRUE(has_saturated_room(1, 0, 2));
    EXPECT_FALSE(has_saturated_room(0, 1, 1));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
