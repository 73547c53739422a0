// How much a slice of a reload's publishing takes: bounded, and never more than the publish
// queue has room for while it drains.

#include "eip2mqtt/core/config/reload_slice.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(ReloadSlice, AnEmptyQueueTakesAWholeSlice) {
    EXPECT_EQ(slice_units(1000, {0, 100000, true}), 1000u);
}

TEST(ReloadSlice, ASliceFillsAtMostHalfTheQueue) {
    EXPECT_EQ(slice_units(1000, {49500, 100000, true}), 500u);
    EXPECT_EQ(slice_units(1000, {0, 1000, true}), 500u);
}

TEST(ReloadSlice, AQueueHalfFullMakesTheReloadWait) {
    EXPECT_EQ(slice_units(1000, {50000, 100000, true}), 0u);
    EXPECT_EQ(slice_units(1000, {100000, 100000, true}), 0u);
}

TEST(ReloadSlice, AQueueOfOneLetsOneThroughAtATime) {
    EXPECT_EQ(slice_units(1000, {0, 1, true}), 1u);
    EXPECT_EQ(slice_units(1000, {1, 1, true}), 0u);
}

TEST(ReloadSlice, DisconnectedTheReloadDoesNotWaitForTheBroker) {
    EXPECT_EQ(slice_units(1000, {100000, 100000, false}), 1000u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
