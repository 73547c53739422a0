// What `sniff --yaml` writes loads as it is: the skeleton of an unconfigured
// exchange, under a configuration's other sections, is a valid configuration whose exchange
// carries what was measured, and an exchange without tags is valid however `tags` is left out.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eip2mqtt/adapters/yaml/discovered_skeleton.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/adapters/yaml/skeleton.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string sections =
    "mqtt:\n"
    "  url: tcp://127.0.0.1:1883\n"
    "  base_topic: acme/site\n";

std::string dump(const core::config::Diagnostics& diagnostics) {
    std::string out;
    for (const auto& d : diagnostics) out += d.to_string() + "\n";
    return out;
}

TEST(SkeletonLoad, TheSkeletonOfSniffedExchangesIsAValidConfiguration) {
    core::exchange::WireSummary turbine;
    turbine.key = {core::wire::ProducerId{0x0A000009}, 3};
    turbine.datagrams = 25;
    turbine.length = turbine.min_length = turbine.max_length = 40;
    turbine.signature = {1, 2};
    turbine.period_ms = 19.6;
    turbine.period_steps = 24;
    turbine.destination = {core::exchange::DestinationKind::multicast, 0xE0000701};
    turbine.clock = core::exchange::ClockState::unsynced;
    turbine.clock_offset_ms = -5000;
    core::exchange::WireSummary bare;  // one datagram, no data, nothing measured
    bare.key = {core::wire::ProducerId{0x0A000009}, 4};
    bare.datagrams = 1;
    const std::vector<core::exchange::WireSummary> summaries{turbine, bare};

    const auto text = sections + adapters::yaml::yaml_skeleton(summaries);
    const auto loaded = load_config_text(text, "skeleton.yaml");
    ASSERT_TRUE(loaded.ok()) << dump(loaded.error()) << text;
    const auto plans = core::config::make_plans(loaded.value());
    ASSERT_EQ(plans.size(), 2u);
    const auto& spec = plans[0].spec;
    EXPECT_EQ(spec.name, "10.0.0.9-3");
    EXPECT_EQ(spec.direction, core::plan::Direction::consume);
    EXPECT_EQ(spec.producer_id, turbine.key.producer_id);
    EXPECT_EQ(spec.exchange_id, 3u);
    EXPECT_EQ(plans[0].length, 40);
    EXPECT_EQ(spec.signature, (core::wire::Signature{1, 2}));
    EXPECT_EQ(spec.period, 20ms);
    EXPECT_EQ(plans[0].topic, "acme/site/10-0-0-9/3");
    EXPECT_TRUE(plans[0].tags.empty());
    EXPECT_EQ(plans[1].spec.name, "10.0.0.9-4");
    EXPECT_EQ(plans[1].length, 1);
    EXPECT_EQ(plans[1].spec.period, 1000ms);
    EXPECT_FALSE(plans[1].spec.signature.is_set());
}

TEST(SkeletonLoad, AnExchangeWithALengthAndNoTagsIsValidWhateverItsTagsKey) {
    for (const std::string tags : {"", "    tags:\n", "    tags: []\n", "    tags: ~\n"}) {
        const auto text = sections +
                          "exchanges:\n"
                          "  - name: ex\n"
                          "    producer_id: 10.0.0.1\n"
                          "    exchange_id: 1\n"
                          "    length: 8\n" +
                          tags;
        const auto loaded = load_config_text(text, "t.yaml");
        ASSERT_TRUE(loaded.ok()) << dump(loaded.error()) << text;
        EXPECT_TRUE(loaded.value().exchanges.at(0).tags.empty()) << text;
    }
}

TEST(SkeletonLoad, TheSkeletonOfDiscoveredExchangesIsAValidConfiguration) {
    adapters::yaml::DiscoveredNode node;
    node.address = "10.20.0.7:7937";
    node.total = 2;
    for (const std::uint32_t id : {3u, 4u}) {
        core::command::ExchangeConfig config;
        config.key = {core::wire::ProducerId{0x0A000009}, id};
        config.length = static_cast<std::uint16_t>(id == 3 ? 40 : 0);
        config.period_ms = id == 3 ? 20 : 0;
        config.signature = 0x0102;
        config.destination_type = core::command::DestinationType::unicast;
        config.destination = 0x0A140001;
        node.exchanges.push_back({{config.key}, config, {}});
    }
    const auto text = sections + adapters::yaml::discovered_skeleton(std::vector{node});
    const auto loaded = load_config_text(text, "discovered.yaml");
    ASSERT_TRUE(loaded.ok()) << dump(loaded.error()) << text;
    const auto& exchanges = loaded.value().exchanges;
    ASSERT_EQ(exchanges.size(), 2u);
    EXPECT_EQ(exchanges[0].spec.length, 40);
    EXPECT_EQ(exchanges[0].spec.period, 20ms);
    EXPECT_EQ(core::wire::to_string(exchanges[0].spec.signature), "1.2");
    EXPECT_EQ(exchanges[1].spec.length, 1);
    EXPECT_EQ(exchanges[1].spec.period, 1000ms);
    EXPECT_TRUE(core::config::validate(loaded.value()).empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
