// `check`'s estimate of the Sparkplug births, alone: one DBIRTH size per plan in the order
// given, a produced exchange's larger than a consumed one's of the same tags (its metrics say
// writable, min and max), and an NBIRTH that grows with every exchange (its state and counters
// are node metrics), whatever the options' primary host and packet limit.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_birth_size.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Direction;
using test::sparkplug_plan;

TEST(SparkplugBirthSizes, OneDbirthPerPlanInOrderAndAnNbirthThatGrowsWithThem) {
    const std::vector<core::plan::ExchangePlan> one{sparkplug_plan("in", Direction::consume)};
    const std::vector<core::plan::ExchangePlan> two{sparkplug_plan("in", Direction::consume),
                                                    sparkplug_plan("out", Direction::produce)};
    const auto single = sparkplug_birth_sizes({"plant1", "gw1", "", 0, 0}, one);
    const auto both = sparkplug_birth_sizes({"plant1", "gw1", "", 0, 0}, two);
    ASSERT_EQ(single.devices.size(), 1u);
    ASSERT_EQ(both.devices.size(), 2u);
    EXPECT_EQ(both.devices[0], single.devices[0]);
    EXPECT_GT(both.devices[1], both.devices[0]);
    EXPECT_GT(single.node, 0u);
    EXPECT_GT(both.node, single.node);
    // Measured as if births went out at once and nothing were too large to measure.
    const auto hosted = sparkplug_birth_sizes({"plant1", "gw1", "scada", 1, 100}, two);
    EXPECT_EQ(hosted.node, both.node);
    EXPECT_EQ(hosted.devices, both.devices);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
