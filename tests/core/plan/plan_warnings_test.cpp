#include "eip2mqtt/core/plan/plan_warnings.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

ExchangePlan plan_of(Direction direction, std::chrono::milliseconds timeout) {
    ExchangePlan plan;
    plan.spec.name = "plc";
    plan.spec.direction = direction;
    plan.timeout = timeout;
    return plan;
}

TEST(PlanWarnings, AConsumedExchangeWithoutTimeoutIsWarnedAboutRestarts) {
    const auto warnings = plan_warnings(plan_of(Direction::consume, 0ms));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("timeout_ms is 0"), std::string::npos);
    EXPECT_NE(warnings[0].find("restart"), std::string::npos);
}

TEST(PlanWarnings, NothingToSayWithATimeoutOrForAProducedExchange) {
    EXPECT_TRUE(plan_warnings(plan_of(Direction::consume, 300ms)).empty());
    EXPECT_TRUE(plan_warnings(plan_of(Direction::produce, 0ms)).empty());
}

ExchangePlan consumed(std::vector<std::string> names, std::optional<std::uint16_t> length) {
    ExchangeSpec spec;
    spec.name = "plc";
    spec.topic = "plc";
    spec.period = 100ms;
    spec.length = length;
    std::uint16_t byte = 0;
    for (auto& name : names) {
        TagSpec tag;
        tag.name = std::move(name);
        tag.address = {byte, 0};
        tag.type = TagType::int_;
        spec.tags.push_back(std::move(tag));
        byte += 2;
    }
    return make_exchange_plan(std::move(spec), "plant");
}

TEST(PlanWarnings, AConsumedExchangeWithoutLengthSaysWhatWasAssumed) {
    const auto warnings = plan_warnings(consumed({"A", "B", "C"}, std::nullopt));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("length is not set: assumed 6 bytes"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[0].find("refused"), std::string::npos) << warnings[0];
    EXPECT_TRUE(plan_warnings(consumed({"A", "B", "C"}, 32)).empty());
}

TEST(PlanWarnings, TagsWhoseNamesDifferOnlyInCaseAreWarned) {
    const auto warnings = plan_warnings(consumed({"SPEED", "Flow", "speed", "FLOW", "Speed"}, 10));
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_NE(warnings[0].find("tags SPEED and speed differ only in case"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[1].find("tags Flow and FLOW"), std::string::npos) << warnings[1];
    EXPECT_NE(warnings[2].find("tags SPEED and Speed"), std::string::npos) << warnings[2];
}

TEST(PlanWarnings, DotsInATopicAreWarnedOnlyForMqtt311) {
    auto plan = consumed({"A"}, 2);
    plan.topic = "acme/line.1/plc";
    const auto warnings = plan_warnings(plan, {.mqtt_3_1_1 = true});
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("topic acme/line.1/plc has dots"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("RabbitMQ"), std::string::npos) << warnings[0];
    EXPECT_TRUE(plan_warnings(plan).empty());
    EXPECT_TRUE(plan_warnings(consumed({"A"}, 2), {.mqtt_3_1_1 = true}).empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
