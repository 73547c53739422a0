// The edge node's metrics alone: bdSeq and Rebirth first, each metric's index its alias (Rebirth
// has none), every one in a birth and only what changed since the last report after it, and
// those of exchanges rebuilt with the running exchanges.

#include "eip2mqtt/app/northbound/sparkplug/node_metrics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "eip2mqtt/app/health/metrics.hpp"
#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::Payload;
using core::plan::Direction;
using core::plan::Value;
using test::sparkplug_plan;

std::vector<std::string> names(const Payload& payload) {
    std::vector<std::string> out;
    for (const auto& metric : payload.metrics) out.push_back(metric.name);
    return out;
}

bool has(const std::vector<std::string>& all, const std::string& name) {
    return std::find(all.begin(), all.end(), name) != all.end();
}

class NodeMetricsTest : public ::testing::Test {
protected:
    core::plan::ExchangePlan in_ = sparkplug_plan("in", Direction::consume);
    core::plan::ExchangePlan out_ = sparkplug_plan("out", Direction::produce);
    NodeMetrics metrics_;
    Payload payload_;
};

TEST_F(NodeMetricsTest, ABirthListsEveryMetricByNameAndIndexBdSeqAndRebirthFirst) {
    metrics_.exchanges_changed({{&in_}, {&out_}});
    metrics_.fill_birth(payload_, 7, 1000);
    const auto all = names(payload_);
    ASSERT_GE(all.size(), 4u);
    EXPECT_EQ(all[0], "bdSeq");
    EXPECT_EQ(payload_.metrics[0].value, adapters::sparkplug::MetricValue{Value{std::int64_t{7}}});
    EXPECT_EQ(all[1], "Node Control/Rebirth");
    EXPECT_EQ(payload_.metrics[1].value, adapters::sparkplug::MetricValue{Value{false}});
    // Each alias is the metric's index, but Rebirth has none (Sparkplug B 3.0).
    EXPECT_FALSE(payload_.metrics[1].alias.has_value());
    for (std::size_t i = 0; i < payload_.metrics.size(); ++i) {
        if (i != 1) {
            EXPECT_EQ(payload_.metrics[i].alias, i);
        }
        EXPECT_EQ(payload_.metrics[i].timestamp_ms, 1000u);
    }
    EXPECT_TRUE(has(all, "Gateway/uptime_s"));
    EXPECT_TRUE(has(all, "Sparkplug/node_births"));
    EXPECT_TRUE(has(all, "Exchanges/in/state"));
    EXPECT_TRUE(has(all, "Exchanges/out/state"));
    // Consumed exchanges' metrics come before produced ones'.
    EXPECT_LT(std::find(all.begin(), all.end(), "Exchanges/in/state"),
              std::find(all.begin(), all.end(), "Exchanges/out/state"));
}

TEST_F(NodeMetricsTest, OnlyWhatChangedSinceTheLastFillIsSentByAlias) {
    metrics_.exchanges_changed({{&in_}, {&out_}});
    metrics_.fill_birth(payload_, 0, 1000);
    const auto born = payload_.metrics.size();
    metrics_.fill_changes(payload_, 2000);
    EXPECT_TRUE(payload_.metrics.empty());

    SparkplugStats stats;
    stats.node_births = 1;
    metrics_.stats(stats);
    ProducedStatus status;
    status.paused = true;
    metrics_.produced_status(out_, status);
    metrics_.fill_changes(payload_, 2000);
    ASSERT_EQ(payload_.metrics.size(), 2u);
    for (const auto& metric : payload_.metrics) {
        EXPECT_TRUE(metric.name.empty());
        ASSERT_TRUE(metric.alias);
        EXPECT_LT(*metric.alias, born);
    }
    EXPECT_EQ(payload_.metrics[1].value, adapters::sparkplug::MetricValue{std::string("paused")});
    metrics_.stats(stats);  // the same again: no change
    metrics_.fill_changes(payload_, 3000);
    EXPECT_TRUE(payload_.metrics.empty());
}

TEST_F(NodeMetricsTest, AValueSetAwayAndBackBetweenTwoFillsIsNoChange) {
    metrics_.exchanges_changed({{&in_}, {&out_}});
    ProducedStatus status;
    metrics_.produced_status(out_, status);
    metrics_.fill_birth(payload_, 0, 1000);  // producing
    status.paused = true;
    metrics_.produced_status(out_, status);
    status.paused = false;
    metrics_.produced_status(out_, status);  // producing again, as the birth said
    metrics_.fill_changes(payload_, 2000);
    EXPECT_TRUE(payload_.metrics.empty());
}

TEST_F(NodeMetricsTest, TheExchangesMetricsFollowTheRunningExchanges) {
    metrics_.exchanges_changed({{&in_}, {&out_}});
    metrics_.fill_birth(payload_, 0, 0);
    const auto with_both = payload_.metrics.size();
    metrics_.exchanges_changed({{}, {&out_}});
    metrics_.fill_birth(payload_, 0, 0);
    const auto all = names(payload_);
    EXPECT_LT(all.size(), with_both);
    EXPECT_FALSE(has(all, "Exchanges/in/state"));
    EXPECT_TRUE(has(all, "Exchanges/out/state"));
    metrics_.exchanges_changed({{}, {}});
    metrics_.fill_birth(payload_, 0, 0);
    EXPECT_FALSE(has(names(payload_), "Exchanges/out/state"));
}

TEST_F(NodeMetricsTest, WidenedForSizingEveryCounterIsAtItsLargest) {
    metrics_.exchanges_changed({{&in_}, {}});
    metrics_.widen_for_sizing();
    metrics_.fill_birth(payload_, 0, 0);
    for (const auto& metric : payload_.metrics) {
        if (metric.datatype != adapters::sparkplug::DataType::uint64) continue;
        EXPECT_EQ(
            metric.value,
            adapters::sparkplug::MetricValue{Value{std::numeric_limits<std::uint64_t>::max()}})
            << metric.name;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
