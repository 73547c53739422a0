// Store and forward over a real journal file, a recording sink and a connection the
// test switches: what is journaled and when, the replay's order, rate and resumption, and what
// leaves the journal (acknowledged entries only, or those no exchange can take any more).

#include "eip2mqtt/app/history/store_and_forward.hpp"

#include "tests/app/history/store_and_forward_rig.hpp"

namespace eip2mqtt::app::history {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using namespace test_rig;

TEST_F(StoreAndForwardTest, JournalsAcceptedChangesOnlyWhileDisconnected) {
    connected_ = true;
    EXPECT_FALSE(saf_->journaling());
    counter(1);
    connected_ = false;
    EXPECT_TRUE(saf_->journaling());
    counter(2, 1010);
    counter(3, 1020, Quality::stale);       // a quality change is history too
    counter(3, 1030, Quality::good, true);  // a republish repeats what is known: not journaled
    counter(9, 1040, Quality::good, false, &produced_);  // an echo of what writers sent: neither
    run_for(10ms);
    EXPECT_EQ(entries(), 2u);
    EXPECT_EQ(saf_->stats().journaled, 2u);
    EXPECT_TRUE(sink_.replayed.empty());  // nothing goes while disconnected
}

TEST_F(StoreAndForwardTest, ReplaysOldestFirstAtTheRateWithTheirTimeAndQuality) {
    for (int i = 1; i <= 30; ++i) counter(i, 1000 + i, i == 30 ? Quality::stale : Quality::good);
    run_for(10ms);
    reconnect();
    run_for(100ms);  // 100 a second: at most 10 in 100 ms
    ASSERT_GE(sink_.replayed.size(), 9u);
    ASSERT_LE(sink_.replayed.size(), 10u);
    EXPECT_EQ(sink_.replayed[0].exchange, "plant");
    EXPECT_EQ(sink_.replayed[0].timestamp_ms, 1001);
    EXPECT_EQ(sink_.replayed[0].quality, Quality::good);
    run_for(300ms);
    ASSERT_EQ(sink_.replayed.size(), 30u);
    std::vector<std::int64_t> expected(30);
    std::iota(expected.begin(), expected.end(), 1);
    EXPECT_EQ(replayed_values(), expected);
    EXPECT_EQ(sink_.replayed.back().quality, Quality::stale);
    EXPECT_EQ(sink_.replayed.back().samples[0].first, 1u);  // the counter's tag index
}

/// A clock on which each read of the monotonic time takes a millisecond.
class SteppingClock final : public core::Clock {
public:
    core::MonoTime monotonic() const override { return now_ += 1ms; }
    core::WallTime wall() const override { return std::chrono::system_clock::now(); }

private:
    mutable core::MonoTime now_ = std::chrono::steady_clock::now();
};

TEST_F(StoreAndForwardTest, ATicksReplayStopsWhenItsTimeIsSpentAndTheRestFollows) {
    // Each read of the clock takes a millisecond: a tick's 2 ms are spent after two entries,
    // where the rate alone would allow ten (an entry of a wide exchange costs that much).
    SteppingClock clock;
    open(1000, &clock);
    for (int i = 1; i <= 30; ++i) counter(i, 1000 + i);
    run_for(10ms);
    reconnect();
    std::vector<std::size_t> per_tick;
    for (int tick = 0; tick < 100 && sink_.replayed.size() < 30; ++tick) {
        const auto before = sink_.replayed.size();
        run_for(10ms);
        per_tick.push_back(sink_.replayed.size() - before);
    }
    EXPECT_EQ(*std::max_element(per_tick.begin(), per_tick.end()), 2u);
    EXPECT_EQ(std::count(per_tick.begin(), per_tick.end(), 0u), 0) << "a tick replayed nothing";
    std::vector<std::int64_t> expected(30);
    std::iota(expected.begin(), expected.end(), 1);
    EXPECT_EQ(replayed_values(), expected);
    acknowledge_all();
    run_for(30ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_FALSE(saf_->stats().replaying);
}

TEST_F(StoreAndForwardTest, AnEntryLeavesTheJournalOnlyOnceAcknowledged) {
    for (int i = 1; i <= 5; ++i) counter(i);
    run_for(10ms);
    reconnect();
    run_for(100ms);
    ASSERT_EQ(sink_.replayed.size(), 5u);
    EXPECT_TRUE(saf_->stats().replaying);
    for (const auto i : {0, 1}) {
        acknowledged_.insert(sink_.replayed[i].token);
        saf_->on_acknowledged(sink_.replayed[i].token);
    }
    run_for(10ms);
    EXPECT_EQ(entries(), 3u);
    EXPECT_EQ(saf_->stats().replayed, 2u);

    // A restart now: the three unacknowledged entries are replayed again, and only they.
    open();
    sink_.replayed.clear();
    acknowledged_.clear();
    reconnect();
    run_for(100ms);
    EXPECT_EQ(replayed_values(), (std::vector<std::int64_t>{3, 4, 5}));
    acknowledge_all();
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_FALSE(saf_->stats().replaying);
}

TEST_F(StoreAndForwardTest, AReconnectDuringTheReplayResumesWithoutSendingAnythingTwice) {
    for (int i = 1; i <= 20; ++i) counter(i);
    run_for(10ms);
    reconnect();
    run_for(50ms);
    const auto sent = sink_.replayed.size();
    ASSERT_GT(sent, 0u);
    ASSERT_LT(sent, 20u);
    // Lost: the client keeps what it was given (and sends it again after the reconnect).
    connected_ = false;
    counter(21);  // the new outage is journaled behind
    run_for(500ms);
    EXPECT_EQ(sink_.replayed.size(), sent);
    reconnect();
    acknowledge_all();  // the client's resent ones are acknowledged after the reconnect
    run_for(500ms);
    std::vector<std::int64_t> expected(21);
    std::iota(expected.begin(), expected.end(), 1);
    EXPECT_EQ(replayed_values(), expected);
    acknowledge_all();
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
}

TEST_F(StoreAndForwardTest, WhatTheClientDroppedUnacknowledgedGoesAgain) {
    for (int i = 1; i <= 3; ++i) counter(i);
    run_for(10ms);
    reconnect();
    run_for(50ms);
    ASSERT_EQ(sink_.replayed.size(), 3u);
    // The client holds none of them and acknowledged none: dropped (a full queue).
    backlog_ = 0;
    run_for(30ms);
    EXPECT_EQ(replayed_values(), (std::vector<std::int64_t>{1, 2, 3, 1, 2, 3}));
}

TEST_F(StoreAndForwardTest, LiveDataWaitingHoldsTheReplayBack) {
    counter(1);
    run_for(10ms);
    reconnect();
    backlog_ = 5000;
    run_for(200ms);
    EXPECT_TRUE(sink_.replayed.empty());
    backlog_.reset();
    run_for(20ms);
    EXPECT_EQ(sink_.replayed.size(), 1u);
}

TEST_F(StoreAndForwardTest, EntriesOfAnExchangeWhoseTagsChangedAreDeletedAndCounted) {
    counter(1);
    counter(2);
    run_for(10ms);
    auto changed = test::test_plan(
        "plant", Direction::consume, 8,
        {test::test_tag("state", 0, TagType::dint), test::test_tag("count", 4, TagType::dint)});
    saf_->exchanges_changed({{&changed}, {}}, {});
    reconnect();
    run_for(100ms);
    EXPECT_TRUE(sink_.replayed.empty());
    EXPECT_EQ(saf_->stats().discarded, 2u);
    EXPECT_EQ(entries(), 0u);
}

TEST_F(StoreAndForwardTest, TheLayoutFingerprintFollowsNamesTypesAndAddresses) {
    const auto base = layout_fingerprint(plant_);
    EXPECT_EQ(base,
              layout_fingerprint(test::test_plan("other", Direction::consume, 8,
                                                 {test::test_tag("state", 0, TagType::dint),
                                                  test::test_tag("counter", 4, TagType::dint)})));
    for (const auto& tags : std::vector<std::vector<core::plan::TagSpec>>{
             {test::test_tag("state", 0, TagType::dint),
              test::test_tag("counter", 4, TagType::udint)},
             {test::test_tag("state", 0, TagType::dint),
              test::test_tag("counter", 6, TagType::dint)},
             {test::test_tag("state", 0, TagType::dint)}}) {
        EXPECT_NE(base, layout_fingerprint(test::test_plan("plant", Direction::consume, 10, tags)));
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::history
