// Several northbounds at once: every event reaches each, in order; a write result
// only the northbound the write came from.

#include "eip2mqtt/app/northbound/fan_out.hpp"

#include <gtest/gtest.h>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/switched_role.hpp"

namespace eip2mqtt::app::northbound {
namespace EIP2MQTT_THIS_FILE {

/// A 4-byte consumed exchange `e1` under `acme`.
core::plan::ExchangePlan e1_plan() {
    core::plan::ExchangeSpec spec;
    spec.name = "e1";
    spec.length = 4;
    spec.topic = "e1";
    return core::plan::make_exchange_plan(spec, "acme");
}

TEST(FanOut, EveryEventReachesEachNorthboundButAResultOnlyItsOrigin) {
    test::RecordingNorthbound first;
    test::RecordingNorthbound second;
    FanOut fan_out;
    fan_out.add(first);
    fan_out.add(second);

    const auto plan = e1_plan();
    const std::vector<TagSample> samples{{0, core::plan::Value{true}}};
    fan_out.exchanges_changed({{&plan}, {}}, {});
    fan_out.tag_samples({plan, core::quality::Quality::good, 1, false, samples});
    fan_out.exchange_state(plan, core::exchange::ConsumeState::stale);
    fan_out.produced_status(plan, ProducedStatus{});
    fan_out.write_result({"r", "", &second}, "refused");
    fan_out.write_result({"r", "", nullptr}, std::nullopt);  // nobody to answer

    const std::vector<std::string> all{"exchanges", "samples", "state", "status"};
    EXPECT_EQ(first.events, all);
    auto with_result = all;
    with_result.push_back("result");
    EXPECT_EQ(second.events, with_result);
    ASSERT_EQ(second.results.size(), 1u);
    EXPECT_EQ(second.results[0].error, "refused");
}

TEST(FanOut, AClosedGateStopsWhatTheExchangesSayButNotTheRunningSetOrTheResultsNorTheTap) {
    test::RecordingNorthbound northbound;
    FanOut fan_out;
    fan_out.add(northbound);
    test::SwitchedRole role;
    bool& open = role.leading;
    fan_out.set_role(role);

    const auto plan = e1_plan();
    const std::vector<TagSample> samples{{0, core::plan::Value{true}}};
    const auto say_everything = [&] {
        fan_out.exchanges_changed({{&plan}, {}}, {});
        fan_out.tag_samples({plan, core::quality::Quality::good, 1, false, samples});
        fan_out.exchange_state(plan, core::exchange::ConsumeState::stale);
        fan_out.produced_status(plan, ProducedStatus{});
        fan_out.write_result({"r", "", &northbound}, "standby");
    };
    test::RecordingNorthbound tap;
    fan_out.set_tap(tap);
    say_everything();
    EXPECT_EQ(northbound.events, (std::vector<std::string>{"exchanges", "result"}));
    // The tap sees the running set and the samples, gate closed or open.
    EXPECT_EQ(tap.events, (std::vector<std::string>{"exchanges", "samples"}));
    open = true;
    northbound.events.clear();
    say_everything();
    EXPECT_EQ(northbound.events,
              (std::vector<std::string>{"exchanges", "samples", "state", "status", "result"}));
    EXPECT_EQ(tap.events.size(), 4u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound
