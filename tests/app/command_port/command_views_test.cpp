// How the command port describes a produced exchange's destination, and the views of no
// exchanges.

#include "eip2mqtt/app/command_port/command_views.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using core::command::DestinationType;

constexpr std::uint32_t address(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d) {
    return (std::uint32_t{a} << 24) | (std::uint32_t{b} << 16) | (std::uint32_t{c} << 8) | d;
}

TEST(CommandViews, MulticastIsTheWhole224Slash4Range) {
    EXPECT_EQ(destination_type(address(224, 0, 0, 0), {}), DestinationType::multicast);
    EXPECT_EQ(destination_type(address(239, 255, 255, 255), {}), DestinationType::multicast);
    EXPECT_EQ(destination_type(address(223, 255, 255, 255), {}), DestinationType::unicast);
    EXPECT_EQ(destination_type(address(240, 0, 0, 0), {}), DestinationType::unicast);
}

TEST(CommandViews, BroadcastIsTheLimitedOneOrOneOfThisHost) {
    const std::vector<std::uint32_t> broadcasts{address(10, 0, 0, 255), address(192, 168, 1, 255)};
    EXPECT_EQ(destination_type(0xFFFFFFFF, {}), DestinationType::broadcast);
    EXPECT_EQ(destination_type(address(192, 168, 1, 255), broadcasts), DestinationType::broadcast);
    EXPECT_EQ(destination_type(address(10, 0, 0, 255), broadcasts), DestinationType::broadcast);
    EXPECT_EQ(destination_type(address(192, 168, 2, 255), broadcasts), DestinationType::unicast);
    EXPECT_EQ(destination_type(address(192, 168, 1, 255), {}), DestinationType::unicast);
}

TEST(CommandViews, NoExchangesNoViews) {
    EXPECT_TRUE(
        command_views({}, {}, CommandViewContext{}, core::MonoTime{}, core::WallTime{}).empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
