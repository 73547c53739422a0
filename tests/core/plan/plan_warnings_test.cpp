#include "eip2mqtt/core/plan/plan_warnings.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::plan {
namespace {

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

}  // namespace
}  // namespace eip2mqtt::core::plan
