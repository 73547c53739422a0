// An exchange with no tags yet: valid as long as its length is known, so that the
// skeleton `sniff --yaml` writes passes `check` and the gateway publishes its `_status` before
// the byte map is known.

#include <gtest/gtest.h>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

Config tagless(std::optional<std::uint16_t> length) {
    Config c;
    c.file = "c.yaml";
    c.gateway.id = "gw";
    c.mqtt.base_topic = "acme/site";
    ExchangeConfig e;
    e.spec.name = "10.0.0.9-3";
    e.spec.topic = "10.0.0.9/3";
    e.spec.direction = plan::Direction::consume;
    e.spec.producer_id = wire::ProducerId{0x0A000009};
    e.spec.exchange_id = 3;
    e.spec.length = length;
    e.spec.period = 20ms;
    e.marks.node = {"c.yaml", 2, 5};
    e.marks.add("name", {"c.yaml", 2, 5});
    c.exchanges.push_back(e);
    return c;
}

TEST(TaglessExchange, WithALengthIsValidAndPlansNoTags) {
    const auto c = tagless(40);
    EXPECT_TRUE(validate(c).empty());
    const auto plans = make_plans(c);
    ASSERT_EQ(plans.size(), 1u);
    EXPECT_TRUE(plans[0].tags.empty());
    EXPECT_EQ(plans[0].length, 40);  // datagrams of any other length are length mismatches
    EXPECT_EQ(plans[0].timeout, 60ms);
    EXPECT_EQ(plans[0].status_topic, "acme/site/10.0.0.9/3/_status");
}

TEST(TaglessExchange, AProducedOneWithALengthIsValidToo) {
    auto c = tagless(8);
    c.exchanges[0].spec.direction = plan::Direction::produce;
    c.exchanges[0].spec.destination = "127.0.0.1";
    EXPECT_TRUE(validate(c).empty());
}

TEST(TaglessExchange, WithoutALengthNothingSaysHowLongItsDatagramsAre) {
    const auto found = validate(tagless(std::nullopt));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].message, "exchange '10.0.0.9-3' needs a length or at least one tag");
    EXPECT_EQ(found[0].mark.line, 2);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
