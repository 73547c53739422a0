// What a reload keeps, starts, stops and clears (docs/operations.md, Reload),
// decided from the plans alone.

#include "eip2mqtt/core/plan/plan_diff.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

ExchangePlan plan(std::string name, std::vector<std::string> tag_names) {
    ExchangeSpec spec;
    spec.name = name;
    spec.topic = std::move(name);
    spec.period = 100ms;
    std::uint16_t byte = 0;
    for (auto& tag_name : tag_names) {
        TagSpec tag;
        tag.name = std::move(tag_name);
        tag.address = {byte, 0};
        tag.type = TagType::int_;
        spec.tags.push_back(std::move(tag));
        byte += 2;
    }
    return make_exchange_plan(std::move(spec), "plant");
}

std::vector<const ExchangePlan*> pointers(const std::vector<ExchangePlan>& plans) {
    std::vector<const ExchangePlan*> out;
    for (const auto& p : plans) out.push_back(&p);
    return out;
}

using Kept = std::vector<std::optional<std::size_t>>;

TEST(PlanDiff, UnchangedExchangesAreKeptWhereverTheyNowStand) {
    const std::vector running{plan("a", {"X"}), plan("b", {"Y"})};
    const std::vector next{plan("b", {"Y"}), plan("a", {"X"})};
    const auto diff = diff_plans(pointers(running), next);
    EXPECT_EQ(diff.kept_from, (Kept{1, 0}));
    EXPECT_TRUE(diff.stopped.empty());
    EXPECT_TRUE(diff.cleared.empty());
}

TEST(PlanDiff, AChangedExchangeRestartsAndOnlyItsVanishedTopicsAreCleared) {
    const std::vector running{plan("a", {"X", "GONE"}), plan("b", {"Y"})};
    const std::vector next{plan("a", {"X"}), plan("b", {"Y"})};
    const auto diff = diff_plans(pointers(running), next);
    EXPECT_EQ(diff.kept_from, (Kept{std::nullopt, 1}));
    EXPECT_EQ(diff.stopped, (std::vector<std::size_t>{0}));
    EXPECT_EQ(diff.cleared, (std::vector<std::string>{"plant/a/GONE"}));
}

TEST(PlanDiff, ARemovedExchangeStopsAndLosesItsStatusAndTags) {
    const std::vector running{plan("a", {"X"}), plan("b", {"Y", "Z"})};
    const std::vector next{plan("a", {"X"})};
    const auto diff = diff_plans(pointers(running), next);
    EXPECT_EQ(diff.kept_from, (Kept{0}));
    EXPECT_EQ(diff.stopped, (std::vector<std::size_t>{1}));
    EXPECT_EQ(diff.cleared, (std::vector<std::string>{"plant/b/Y", "plant/b/Z", "plant/b/_meta",
                                                      "plant/b/_status"}));
}

TEST(PlanDiff, ATopicAnotherExchangeNowPublishesIsNotCleared) {
    // Exchange "b" is renamed "c" but keeps b's topic: its subscribers must keep their values.
    const std::vector running{plan("b", {"Y"})};
    auto renamed = plan("b", {"Y"});
    renamed.spec.name = "c";
    const std::vector next{renamed};
    const auto diff = diff_plans(pointers(running), next);
    EXPECT_EQ(diff.kept_from, (Kept{std::nullopt}));
    EXPECT_EQ(diff.stopped, (std::vector<std::size_t>{0}));
    EXPECT_TRUE(diff.cleared.empty());
}

TEST(PlanDiff, AFirstStartStartsEverything) {
    const std::vector next{plan("a", {"X"})};
    const auto diff = diff_plans({}, next);
    EXPECT_EQ(diff.kept_from, (Kept{std::nullopt}));
    EXPECT_TRUE(diff.stopped.empty());
    EXPECT_TRUE(diff.cleared.empty());
}

TEST(PlanDiff, TheDescriptionNamesTheExchangesKeptChangedStartedAndStopped) {
    const std::vector<ExchangePlan> running{plan("a", {"X"}), plan("b", {"X"}), plan("c", {"X"})};
    const std::vector<ExchangePlan> next{plan("a", {"X"}), plan("c", {"Y"}), plan("d", {"X"})};
    const auto diff = diff_plans(pointers(running), next);
    EXPECT_EQ(describe_diff(diff, pointers(running), next),
              "kept a; changed c; started d; stopped b");
}

TEST(PlanDiff, TheDescriptionIsBoundedAndSaysNothingForNothing) {
    std::vector<ExchangePlan> next;
    for (const auto* name : {"a", "b", "c", "d"}) next.push_back(plan(name, {"X"}));
    const auto diff = diff_plans({}, next);
    EXPECT_EQ(describe_diff(diff, {}, next, 2), "started a, b and 2 more");
    EXPECT_EQ(describe_diff(diff_plans({}, {}), {}, {}), "nothing");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
