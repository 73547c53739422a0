// A wall time as the protocol's headers and command answers carry it.

#include <gtest/gtest.h>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

TEST(WireTime, SplitsIntoWholeSecondsAndTheNanosecondsPastThem) {
    const WallTime wall{std::chrono::seconds(1700000000) + std::chrono::nanoseconds(123456789)};
    const auto t = wire_time(wall);
    EXPECT_EQ(t.seconds, 1700000000u);
    EXPECT_EQ(t.nanoseconds, 123456789u);
}

TEST(WireTime, AWholeSecondHasNoNanoseconds) {
    const auto t = wire_time(WallTime{std::chrono::seconds(42)});
    EXPECT_EQ(t.seconds, 42u);
    EXPECT_EQ(t.nanoseconds, 0u);
}

TEST(WireTime, TheLastNanosecondOfASecondStaysInIt) {
    const auto t =
        wire_time(WallTime{std::chrono::seconds(5) + std::chrono::nanoseconds(999999999)});
    EXPECT_EQ(t.seconds, 5u);
    EXPECT_EQ(t.nanoseconds, 999999999u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
