// The sparklines of the status page: one point per 10 s step of the gateway's clock, a step in
// which a tag did not change keeping its value, null before the first value and after a line
// has passed without one; text tags have none, and the bound gives rows to the exchanges in
// order until it is spent.

#include "eip2mqtt/app/status/sparklines.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::app::status {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Direction;
using core::plan::TagType;
using json = nlohmann::json;
using namespace std::chrono_literals;

class SparklinesTest : public ::testing::Test {
protected:
    SparklinesTest() {
        auto name = test::test_tag("NAME", 8, TagType::string);
        name.count = 4;
        plan_ = test::test_plan("pump", Direction::consume, 12,
                                {test::test_tag("SPEED", 0, TagType::dint), name,
                                 test::test_tag("FLOW", 4, TagType::real)});
        ExchangeSet running;
        running.consumed = {&plan_};
        lines_.exchanges_changed(running, {});
    }
    void report(std::vector<core::plan::TagSample> samples) {
        lines_.tag_samples({plan_, core::quality::Quality::good, clock_.wall_ms(), false, samples});
    }
    /// The tag's sparkline now; null when it has none.
    json line(std::size_t tag) const {
        std::string out = "{\"x\":0";
        lines_.append_json(out, plan_, tag, clock_.wall_ms());
        const auto doc = json::parse(out + "}");
        return doc.contains("sparkline") ? doc["sparkline"] : json();
    }

    test::FakeClock clock_;  // 1767225600 s: a step's start
    core::plan::ExchangePlan plan_;
    Sparklines lines_{clock_};
};

TEST_F(SparklinesTest, EachStepHoldsTheTagsLastValueAndKeepsItWhileItDoesNotChange) {
    EXPECT_EQ(lines_.tags(), 2u) << "SPEED and FLOW; NAME is text";
    EXPECT_TRUE(line(1).is_null());
    ASSERT_EQ(line(0).size(), Sparklines::points);
    EXPECT_TRUE(line(0).back().is_null()) << "no value yet";
    report({{0, std::int64_t{5}}, {2, 1.5}});
    clock_.advance(3s);
    report({{0, std::int64_t{6}}});  // the same step: the last value wins
    clock_.advance(20s);
    report({{0, std::int64_t{7}}});
    clock_.advance(10s);
    const auto speed = line(0);
    ASSERT_EQ(speed.size(), Sparklines::points);
    const std::vector<json> last(speed.end() - 5, speed.end());
    EXPECT_EQ(last, (std::vector<json>{nullptr, 6, 6, 7, 7}));
    EXPECT_EQ(line(2).back(), 1.5);
}

TEST_F(SparklinesTest, ALineWithoutAValueForgetsTheOldOnes) {
    report({{0, std::int64_t{5}}});
    clock_.advance(Sparklines::step * (Sparklines::points / 2));
    EXPECT_EQ(line(0).back(), 5) << "carried while nothing new came";
    EXPECT_TRUE(line(0).front().is_null()) << "a step before the first value";
    clock_.advance(Sparklines::step * 2 * Sparklines::points);
    report({{0, std::int64_t{8}}});
    const auto speed = line(0);
    EXPECT_EQ(speed.back(), 8);
    EXPECT_EQ(speed[speed.size() - 2], 5) << "the last value before, carried on";
}

TEST(Sparklines, TheBoundGivesRowsInOrderUntilItIsSpent) {
    test::FakeClock clock;
    Sparklines lines{clock};
    std::vector<core::plan::ExchangePlan> plans;
    constexpr std::size_t per_exchange = 300;
    for (std::size_t e = 0; e * per_exchange <= Sparklines::max_tags; ++e) {
        std::vector<core::plan::TagSpec> tags;
        for (std::size_t t = 0; t < per_exchange; ++t) {
            tags.push_back(test::test_tag("T" + std::to_string(t),
                                          static_cast<std::uint16_t>(4 * t), TagType::dint));
        }
        plans.push_back(test::test_plan("e" + std::to_string(e), Direction::consume,
                                        4 * per_exchange, std::move(tags)));
    }
    ExchangeSet running;
    for (const auto& plan : plans) running.consumed.push_back(&plan);
    lines.exchanges_changed(running, {});
    EXPECT_EQ(lines.tags(), Sparklines::max_tags);
    std::string first;
    std::string last;
    lines.append_json(first, plans.front(), 0, 0);
    lines.append_json(last, plans.back(), per_exchange - 1, 0);
    EXPECT_FALSE(first.empty());
    EXPECT_TRUE(last.empty()) << "beyond the bound: no sparkline";
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::status
