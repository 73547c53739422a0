#include "eip2mqtt/core/plan/exchange_plan.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

TagSpec tag(std::string name, std::uint16_t byte, std::uint8_t bit, TagType type) {
    TagSpec spec;
    spec.name = std::move(name);
    spec.address = {byte, bit};
    spec.type = type;
    return spec;
}

ExchangeSpec turbine() {
    ExchangeSpec spec;
    spec.name = "turbine1";
    spec.topic = "turbine1";
    spec.period = 100ms;
    spec.tags = {tag("PRESSAO_OK", 120, 7, TagType::bit), tag("PRESSAO", 126, 0, TagType::int_)};
    return spec;
}

TEST(ResolvedLength, IsTheConfiguredLength) {
    auto spec = turbine();
    spec.length = 372;
    EXPECT_EQ(resolved_length(spec), 372);
}

TEST(ResolvedLength, DefaultsToTheEndOfTheLastTag) {
    auto spec = turbine();
    EXPECT_EQ(resolved_length(spec), 128);
    spec.tags.push_back(tag("DENSIDADE", 368, 0, TagType::real));
    EXPECT_EQ(resolved_length(spec), 372);
    spec.tags.push_back(tag("FLAG", 400, 3, TagType::bit));
    EXPECT_EQ(resolved_length(spec), 401);
}

TEST(ResolvedLength, IsZeroWithoutTagsOrLength) { EXPECT_EQ(resolved_length(ExchangeSpec{}), 0); }

TEST(ExchangePlans, TopicsFollowTheContract) {
    const auto plan = make_exchange_plan(turbine(), "acme/blumenau/generation");
    EXPECT_EQ(plan.topic, "acme/blumenau/generation/turbine1");
    EXPECT_EQ(plan.status_topic, "acme/blumenau/generation/turbine1/_status");
    EXPECT_EQ(plan.values_topic, "acme/blumenau/generation/turbine1/_values");
    EXPECT_EQ(plan.set_topic, "acme/blumenau/generation/turbine1/set");
    ASSERT_EQ(plan.tags.size(), 2u);
    EXPECT_EQ(plan.tag_topic(plan.tags[0]), "acme/blumenau/generation/turbine1/PRESSAO_OK");
    EXPECT_EQ(plan.tag_topic(plan.tags[1]), "acme/blumenau/generation/turbine1/PRESSAO");
    EXPECT_EQ(plan.tags[1].spec.name, "PRESSAO");
    EXPECT_EQ(plan.spec.tags.size(), 2u);
}

TEST(ExchangePlans, NestedExchangeTopic) {
    auto spec = turbine();
    spec.topic = "turbine1/setpoints";
    const auto plan = make_exchange_plan(spec, "acme");
    EXPECT_EQ(plan.topic, "acme/turbine1/setpoints");
    EXPECT_EQ(plan.tag_topic(plan.tags[1]), "acme/turbine1/setpoints/PRESSAO");
}

TEST(ExchangePlans, TimeoutDefaultsToThreePeriods) {
    const auto plan = make_exchange_plan(turbine(), "acme");
    EXPECT_EQ(plan.timeout, 300ms);
}

TEST(ExchangePlans, ExplicitTimeoutWinsAndZeroDisables) {
    auto spec = turbine();
    spec.timeout = 1000ms;
    EXPECT_EQ(make_exchange_plan(spec, "acme").timeout, 1000ms);
    spec.timeout = 0ms;
    EXPECT_EQ(make_exchange_plan(spec, "acme").timeout, 0ms);
}

TEST(ExchangePlans, ProducedExchangesHaveNoTimeout) {
    auto spec = turbine();
    spec.direction = Direction::produce;
    EXPECT_EQ(make_exchange_plan(spec, "acme").timeout, 0ms);
}

TEST(ExchangePlans, LengthIsResolved) {
    auto plan = make_exchange_plan(turbine(), "acme");
    EXPECT_EQ(plan.length, 128);
    auto spec = turbine();
    spec.length = 372;
    EXPECT_EQ(make_exchange_plan(spec, "acme").length, 372);
}

TEST(ExchangePlans, KeyIsTheProducerExchangePair) {
    auto spec = turbine();
    spec.producer_id = wire::ProducerId{0xC0A8010E};
    spec.exchange_id = 2;
    const auto key = make_exchange_plan(spec, "acme").key();
    EXPECT_EQ(key.producer_id.value, 0xC0A8010Eu);
    EXPECT_EQ(key.exchange_id, 2u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
