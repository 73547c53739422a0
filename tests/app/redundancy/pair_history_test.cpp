// A pair's samples across a takeover, against a recording history sink and a fake clock: what
// each unit keeps, the watermarks the leader learns from its acknowledgements, and what a new
// leader replays. The window's and the watermarks' own rules are tested in
// tests/core/redundancy/.

#include "eip2mqtt/app/redundancy/pair_history.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_history_sink.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::quality::Quality;
using core::redundancy::AckedWatermarks;
using core::redundancy::SampleKey;

core::plan::ExchangePlan consumed(const std::string& name, std::chrono::milliseconds period) {
    auto plan = test::test_plan(name, core::plan::Direction::consume, 4,
                                {test::test_tag("COUNT", 0, core::plan::TagType::dint)});
    plan.spec.period = period;
    return plan;
}

class PairHistoryTest : public ::testing::Test {
protected:
    PairHistoryTest() { history_.exchanges_changed({{&line_, &tank_}, {}}, {}); }

    /// Sample `n` of `plan` (request id n, COUNT = n), 20 ms after the last one.
    SampleBatch sample(const core::plan::ExchangePlan& plan, std::uint16_t n) {
        clock_.advance(20ms);
        tags_.assign({{0, core::plan::Value{std::int64_t{n}}}});
        return {plan, Quality::good, 1000 + n, false, tags_, SampleKey{n}};
    }
    void report(const core::plan::ExchangePlan& plan, std::uint16_t n) {
        history_.tag_samples(sample(plan, n));
    }
    /// Each replayed sample as (exchange, COUNT).
    std::vector<std::pair<std::string, std::int64_t>> replayed() const {
        std::vector<std::pair<std::string, std::int64_t>> out;
        for (const auto& r : sink_.replayed) out.emplace_back(r.exchange, r.samples.at(0).second);
        return out;
    }

    core::plan::ExchangePlan line_ = consumed("line", 20ms);
    core::plan::ExchangePlan tank_ = consumed("tank", 100ms);
    std::vector<TagSample> tags_;
    test::FakeClock clock_;
    test::RecordingHistorySink sink_;
    std::uint64_t backlog_ = 0;
    PairHistory history_{{1000ms}, sink_, [this] { return backlog_; }, clock_};
};

TEST_F(PairHistoryTest, TheLeadersWatermarkIsItsNewestAcknowledgedSample) {
    report(line_, 1);
    const auto first = history_.token_for(sample(line_, 1));
    const auto second = history_.token_for(sample(line_, 2));
    EXPECT_TRUE(history_.watermarks().empty());
    EXPECT_TRUE(history_.on_acknowledged(second));
    EXPECT_TRUE(history_.on_acknowledged(first));
    EXPECT_EQ(history_.watermarks(), (Watermarks{{"line", SampleKey{2}}}));
    // A journal entry's token is store and forward's.
    EXPECT_FALSE(history_.on_acknowledged(17));
}

TEST_F(PairHistoryTest, TakingOverReplaysWhatCameAfterTheHeardWatermarksOldestFirst) {
    for (std::uint16_t n = 1; n <= 5; ++n) {
        report(line_, n);
        if (n % 2 == 0) report(tank_, n / 2);
    }
    history_.heard({{"line", SampleKey{3}}, {"tank", SampleKey{1}}});
    history_.took_over(clock_.monotonic());
    EXPECT_EQ(replayed(), (std::vector<std::pair<std::string, std::int64_t>>{
                              {"line", 4}, {"tank", 2}, {"line", 5}}));
    EXPECT_EQ(sink_.replayed.front().timestamp_ms, 1004);
    EXPECT_EQ(history_.counters().replayed, 3u);
    // The new leader's renewals say the heard watermarks until its replay is acknowledged.
    EXPECT_EQ(history_.watermarks(), (Watermarks{{"line", SampleKey{3}}, {"tank", SampleKey{1}}}));
    for (const auto& r : sink_.replayed) EXPECT_TRUE(history_.on_acknowledged(r.token));
    EXPECT_EQ(history_.watermarks(), (Watermarks{{"line", SampleKey{5}}, {"tank", SampleKey{2}}}));
}

TEST_F(PairHistoryTest, WithoutAWatermarkTheLastTwoTakeoversOfSamples) {
    report(line_, 1);
    clock_.advance(2s);
    report(line_, 2);
    report(line_, 3);
    history_.took_over(clock_.monotonic());
    EXPECT_EQ(replayed(),
              (std::vector<std::pair<std::string, std::int64_t>>{{"line", 2}, {"line", 3}}));
    EXPECT_TRUE(history_.watermarks().empty());
}

TEST_F(PairHistoryTest, TheReplayWaitsWhileTheConnectionIsBacklogged) {
    for (std::uint16_t n = 1; n <= 3; ++n) report(line_, n);
    backlog_ = 1000;
    history_.took_over(clock_.monotonic());
    EXPECT_TRUE(sink_.replayed.empty());
    EXPECT_TRUE(history_.replaying());
    report(line_, 4);  // live: not the replay's
    backlog_ = 0;
    history_.on_tick();
    EXPECT_EQ(replayed().size(), 3u);
    EXPECT_FALSE(history_.replaying());
}

TEST_F(PairHistoryTest, TheSessionsSinkGetsTheSameReplayInOrderOnceItIsReady) {
    test::RecordingHistorySink node;
    bool born = false;
    std::uint64_t node_backlog = 0;
    history_.add_session_sink(
        node, [&] { return born; }, [&] { return node_backlog; });
    for (std::uint16_t n = 1; n <= 3; ++n) report(line_, n);
    report(tank_, 1);
    history_.heard({{"line", SampleKey{1}}});
    history_.took_over(clock_.monotonic());
    EXPECT_EQ(replayed().size(), 3u);    // the JSON tree's at once
    EXPECT_TRUE(node.replayed.empty());  // the node is not born yet
    EXPECT_TRUE(history_.replaying());   // kept for it
    born = true;
    node_backlog = 1000;  // its connection is full: it waits
    history_.on_tick();
    EXPECT_TRUE(node.replayed.empty());
    node_backlog = 0;
    history_.on_tick();
    ASSERT_EQ(node.replayed.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(node.replayed[i].exchange, sink_.replayed[i].exchange);
        EXPECT_EQ(node.replayed[i].samples, sink_.replayed[i].samples);
        EXPECT_EQ(node.replayed[i].token, 0u);  // the watermarks are the JSON tree's alone
    }
    EXPECT_EQ(history_.session_replayed(), 3u);
    EXPECT_FALSE(history_.replaying());
}

TEST_F(PairHistoryTest, SteppingDownEndsTheReplayAndForgetsItsWatermarks) {
    report(line_, 1);
    history_.on_acknowledged(history_.token_for(sample(line_, 1)));
    backlog_ = 1000;
    history_.took_over(clock_.monotonic());
    history_.stood_by();
    backlog_ = 0;
    history_.on_tick();
    EXPECT_TRUE(sink_.replayed.empty());
    EXPECT_TRUE(history_.watermarks().empty());
}

TEST_F(PairHistoryTest, TheReplayWaitsForItsGateAndAUnitFencedMeanwhileReplaysNothing) {
    // The gate: a renewal sent since it leads acknowledged (Lease::renewed_since_leading).
    bool renewed = false;
    history_.set_replay_gate([&] { return renewed; });
    for (std::uint16_t n = 1; n <= 3; ++n) report(line_, n);
    history_.took_over(clock_.monotonic());
    history_.on_tick();
    EXPECT_TRUE(sink_.replayed.empty());
    EXPECT_TRUE(history_.replaying());
    // Cut off as it took over: no renewal acknowledged, its lease lapsed.
    history_.stood_by();
    renewed = true;
    history_.on_tick();
    EXPECT_TRUE(sink_.replayed.empty());
    // Leading again, and reaching the broker: the replay goes.
    renewed = false;
    history_.took_over(clock_.monotonic());
    renewed = true;
    history_.on_tick();
    EXPECT_EQ(replayed().size(), 3u);
}

TEST_F(PairHistoryTest, ALeaderThatStoodByAndLeadsAgainReplaysOnlyWhatCameAfterItsOwn) {
    report(line_, 1);
    history_.took_over(clock_.monotonic());  // nothing heard: sample 1 goes on `_history`
    report(line_, 2);
    history_.on_acknowledged(history_.token_for(sample(line_, 2)));
    report(line_, 3);
    history_.stood_by();  // its lease lapsed; nobody else led meanwhile
    history_.took_over(clock_.monotonic());
    EXPECT_EQ(replayed(),
              (std::vector<std::pair<std::string, std::int64_t>>{{"line", 1}, {"line", 3}}));
}

TEST_F(PairHistoryTest, AReloadKeepsAKeptExchangesWindowAndDropsAStoppedOnesReplay) {
    report(line_, 1);
    report(tank_, 1);
    backlog_ = 1000;
    history_.took_over(clock_.monotonic());
    history_.exchanges_changed({{&line_}, {}}, {});
    backlog_ = 0;
    history_.on_tick();
    EXPECT_EQ(replayed(), (std::vector<std::pair<std::string, std::int64_t>>{{"line", 1}}));
    history_.stood_by();
    report(line_, 2);
    history_.took_over(clock_.monotonic());
    EXPECT_EQ(replayed().size(), 3u);  // line 1 again (no watermark heard), then 2
}

TEST_F(PairHistoryTest, OnlyNamedSamplesOfConsumedExchangesAreKept) {
    const auto produced = test::test_produced_plan();
    tags_.assign({{0, core::plan::Value{std::int64_t{1}}}});
    history_.tag_samples({line_, Quality::good, 1, true, tags_});  // a republish
    history_.tag_samples({produced, Quality::good, 1, false, tags_, SampleKey{1}});
    EXPECT_EQ(history_.token_for({produced, Quality::good, 1, false, tags_, SampleKey{1}}), 0u);
    history_.took_over(clock_.monotonic());
    EXPECT_TRUE(sink_.replayed.empty());
}

TEST(PairHistoryBounds, SamplesPushedOutBeforeTheirTimeAreCounted) {
    auto line = consumed("line", 20ms);
    test::FakeClock clock;
    test::RecordingHistorySink sink;
    PairHistory history{
        {1000ms, 3 * core::redundancy::SampleWindow::bytes_of(1)}, sink, nullptr, clock};
    history.exchanges_changed({{&line}, {}}, {});
    std::vector<TagSample> tags{{0, core::plan::Value{std::int64_t{1}}}};
    for (std::uint16_t n = 1; n <= 5; ++n) {
        history.tag_samples({line, Quality::good, 1, false, tags, SampleKey{n}});
    }
    EXPECT_EQ(history.counters().window_overflow, 2u);
    history.took_over(clock.monotonic());
    EXPECT_EQ(sink.replayed.size(), 3u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
