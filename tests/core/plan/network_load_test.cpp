#include "eip2mqtt/core/plan/network_load.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

ExchangePlan plan(std::string name, Direction direction, std::chrono::milliseconds period,
                  std::uint16_t length, std::string destination) {
    ExchangeSpec spec;
    spec.name = std::move(name);
    spec.topic = spec.name;
    spec.direction = direction;
    spec.period = period;
    spec.length = length;
    spec.destination = std::move(destination);
    return make_exchange_plan(std::move(spec), "acme");
}

TEST(WireBytes, CountsEthernetIpUdpAndTheEipHeaderBesideTheData) {
    // 8 + 14 + 20 + 8 + 32 + 4 + 12.
    EXPECT_EQ(wire_overhead_bytes, 98u);
    EXPECT_EQ(wire_bytes(1), 99u);
    EXPECT_EQ(wire_bytes(1400), 1498u);
    // A captured datagram's size already holds the EIP header.
    EXPECT_EQ(wire_bytes_of_datagram(32 + 1), 99u);
    EXPECT_EQ(wire_bytes_of_datagram(20), 86u);  // a datagram too short for a header
}

TEST(ConfiguredRate, AddsConsumedAndProducedExchangesAtTheirPeriods) {
    // What a capture of the network should see: the PLC's datagrams and the gateway's.
    const auto rate = configured_rate({plan("a", Direction::produce, 20ms, 52, "10.0.0.5"),
                                       plan("in", Direction::consume, 2ms, 1400, "")});
    EXPECT_DOUBLE_EQ(rate.datagrams_per_s, 50 + 500);
    EXPECT_DOUBLE_EQ(rate.bits_per_s, 50 * 150 * 8 + 500 * 1498 * 8);
    EXPECT_DOUBLE_EQ(configured_rate({}).bits_per_s, 0);
}

TEST(NetworkLoad, AddsProducedExchangesOnlyPerDestinationInFirstAppearanceOrder) {
    const auto load = network_load({plan("a", Direction::produce, 20ms, 52, "10.0.0.5"),
                                    plan("in", Direction::consume, 2ms, 1400, ""),
                                    plan("b", Direction::produce, 1000ms, 2, "10.0.0.6:18300"),
                                    plan("c", Direction::produce, 20ms, 52, "10.0.0.5")});
    ASSERT_EQ(load.exchanges.size(), 3u);
    EXPECT_EQ(load.exchanges[0].name, "a");
    EXPECT_DOUBLE_EQ(load.exchanges[0].datagrams_per_s, 50);
    EXPECT_DOUBLE_EQ(load.exchanges[0].bits_per_s, 50 * 150 * 8);
    EXPECT_DOUBLE_EQ(load.exchanges[1].bits_per_s, 1 * 100 * 8);
    ASSERT_EQ(load.destinations.size(), 2u);
    EXPECT_EQ(load.destinations[0].destination, "10.0.0.5");
    EXPECT_EQ(load.destinations[0].exchanges, 2u);
    EXPECT_DOUBLE_EQ(load.destinations[0].datagrams_per_s, 100);
    EXPECT_EQ(load.destinations[1].destination, "10.0.0.6:18300");
    EXPECT_DOUBLE_EQ(load.datagrams_per_s, 101);
    EXPECT_DOUBLE_EQ(load.bits_per_s, 2 * 60000 + 800);
    EXPECT_DOUBLE_EQ(load.link_share(1), 120800 / 1e6);
}

TEST(NetworkLoad, PhasesSpreadEachProducedExchangeOverItsPeriodAsTheSchedulerDoes) {
    const auto load = network_load(
        {plan("a", Direction::produce, 10ms, 1, "h"), plan("in", Direction::consume, 10ms, 1, ""),
         plan("b", Direction::produce, 10ms, 1, "h"), plan("c", Direction::produce, 30ms, 1, "h"),
         plan("d", Direction::produce, 8ms, 1, "h")});
    EXPECT_EQ(load.exchanges[0].phase, 0ms);
    EXPECT_EQ(load.exchanges[1].phase, 2500us);  // 10 ms x 1 / 4
    EXPECT_EQ(load.exchanges[2].phase, 15ms);    // 30 ms x 2 / 4
    EXPECT_EQ(load.exchanges[3].phase, 6ms);     // 8 ms x 3 / 4
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
