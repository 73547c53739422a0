// Store and forward over a real journal file, a recording sink and a connection the
// test switches: what is journaled and when, the replay's order, rate and resumption, and what
// leaves the journal (acknowledged entries only, or those no exchange can take any more).

#include "eip2mqtt/app/history/store_and_forward.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/recording_history_sink.hpp"

namespace eip2mqtt::app::history {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::plan::Direction;
using core::plan::TagType;
using core::quality::Quality;
using test::RecordingHistorySink;

class StoreAndForwardTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("eip2mqtt_saf_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        open();
    }
    void TearDown() override {
        saf_.reset();
        fs::remove_all(dir_);
    }

    void open(std::uint32_t replay_rate = 100, const Clock* clock = nullptr) {
        saf_.reset();
        std::string set_aside;
        auto journal = adapters::history::Journal::open(
            {(dir_ / "history.sqlite").string(), 256ull << 20}, set_aside);
        StoreAndForwardOptions options{replay_rate, 1000ms};
        if (clock) options.clock = clock;
        saf_ = std::make_unique<StoreAndForward>(
            std::move(journal), std::move(options),
            LinkProbe{[this] { return connected_; }, [this] { return backlog(); }}, sink_);
        saf_->exchanges_changed({{&plant_}, {&produced_}}, {});
    }

    /// One datagram's change of the counter (tag 1), at `timestamp`.
    void counter(std::int64_t value, std::int64_t timestamp = 1000, Quality quality = Quality::good,
                 bool all_tags = false, const core::plan::ExchangePlan* plan = nullptr) {
        const std::vector<TagSample> samples{{1, core::plan::Value{value}}};
        saf_->tag_samples({plan ? *plan : plant_, quality, timestamp, all_tags, samples});
    }

    /// Ticks every 10 ms for `duration`; the journal's writer is waited for after each tick,
    /// so that what a tick hands over is in the journal at the next.
    void run_for(std::chrono::milliseconds duration) {
        for (auto t = 0ms; t < duration; t += 10ms) {
            now_ += 10ms;
            saf_->on_tick(now_);
            saf_->flush();
        }
    }
    void reconnect() {
        connected_ = true;
        saf_->on_connected(now_);
    }
    void acknowledge_all() {
        for (const auto& r : sink_.replayed) {
            if (acknowledged_.insert(r.token).second) saf_->on_acknowledged(r.token);
        }
    }
    /// By default the client holds what it was given until it is acknowledged.
    std::uint64_t backlog() const {
        return backlog_ ? *backlog_ : sink_.replayed.size() - acknowledged_.size();
    }
    std::vector<std::int64_t> replayed_values(std::size_t from = 0) const {
        std::vector<std::int64_t> values;
        for (std::size_t i = from; i < sink_.replayed.size(); ++i) {
            values.push_back(sink_.replayed[i].samples.at(0).second);
        }
        return values;
    }
    std::uint64_t entries() { return saf_->stats().journal.entries; }

    core::plan::ExchangePlan plant_ = test::test_plan(
        "plant", Direction::consume, 8,
        {test::test_tag("state", 0, TagType::dint), test::test_tag("counter", 4, TagType::dint)});
    core::plan::ExchangePlan produced_ = test::test_plan("setpoints", Direction::produce, 4,
                                                         {test::test_tag("sp", 0, TagType::dint)});
    fs::path dir_;
    bool connected_ = false;
    std::optional<std::uint64_t> backlog_;
    std::set<std::uint64_t> acknowledged_;
    core::MonoTime now_ = std::chrono::steady_clock::now();
    RecordingHistorySink sink_;
    std::unique_ptr<StoreAndForward> saf_;
};

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
class SteppingClock final : public Clock {
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

/// A second northbound with a connection of its own (the Sparkplug node's), which the test
/// switches; its client holds what it was given until acknowledged, or drops it all when its
/// connection goes (session-bound).
struct OtherNorthbound {
    RecordingHistorySink sink;
    bool connected = false;
    std::size_t acknowledged = 0;  ///< of sink.replayed, in order
    std::size_t dropped = 0;       ///< of sink.replayed, lost with a connection
    LinkProbe link() {
        return {[this] { return connected; },
                [this] { return sink.replayed.size() - acknowledged - dropped; }};
    }
    void acknowledge_all(StoreAndForward& saf) {
        for (; acknowledged + dropped < sink.replayed.size(); ++acknowledged) {
            saf.on_acknowledged(sink, sink.replayed[acknowledged + dropped].token);
        }
    }
    std::vector<std::int64_t> values() const {
        std::vector<std::int64_t> out;
        for (const auto& r : sink.replayed) out.push_back(r.samples.at(0).second);
        return out;
    }
};

TEST_F(StoreAndForwardTest, AnotherSinkReplaysOnceItsOwnConnectionIsUp) {
    OtherNorthbound sparkplug;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 3; ++i) counter(i, 1000 + i);
    run_for(10ms);
    reconnect();  // the JSON tree's connection; the other is not back yet
    run_for(50ms);
    EXPECT_EQ(sink_.replayed.size(), 3u);
    EXPECT_TRUE(sparkplug.sink.replayed.empty());
    acknowledge_all();
    run_for(20ms);
    EXPECT_EQ(entries(), 3u) << "deleted before the other northbound had them";

    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(50ms);
    ASSERT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 2, 3}));
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(sparkplug.sink.replayed[i].timestamp_ms, sink_.replayed[i].timestamp_ms);
        EXPECT_EQ(sparkplug.sink.replayed[i].token, sink_.replayed[i].token);
    }
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_FALSE(saf_->stats().replaying);
    EXPECT_EQ(saf_->stats().replayed, 3u);
}

TEST_F(StoreAndForwardTest, WhatAnotherSinksConnectionLostGoesAgainOnItsNextConnection) {
    OtherNorthbound sparkplug;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 5; ++i) counter(i, 1000 + i);
    run_for(10ms);
    reconnect();
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(100ms);
    acknowledge_all();
    ASSERT_EQ(sparkplug.sink.replayed.size(), 5u);
    // Two acknowledged, then the connection goes with the other three.
    for (int i = 0; i < 2; ++i) {
        saf_->on_acknowledged(sparkplug.sink, sparkplug.sink.replayed[i].token);
    }
    sparkplug.acknowledged = 2;
    sparkplug.dropped = 3;
    sparkplug.connected = false;
    run_for(100ms);
    EXPECT_EQ(entries(), 3u);
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(100ms);
    EXPECT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 2, 3, 4, 5, 3, 4, 5}));
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_EQ(sink_.replayed.size(), 5u);  // the JSON tree's replay is its own: nothing again
}

TEST_F(StoreAndForwardTest, WhatAnotherSinkPublishedLiveIsNotWaitedFor) {
    // The other northbound's connection stayed up through the first one's outage: it published
    // those samples live, and the journal does not keep them for it.
    OtherNorthbound sparkplug;
    sparkplug.connected = true;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 3; ++i) counter(i, 1000 + i);
    run_for(20ms);
    reconnect();
    run_for(50ms);
    acknowledge_all();
    run_for(100ms);
    EXPECT_EQ(entries(), 3u) << "a connection that went may not have been noticed yet";
    run_for(4s);
    EXPECT_TRUE(sparkplug.sink.replayed.empty());
    EXPECT_EQ(entries(), 0u);
}

TEST_F(StoreAndForwardTest, AnEntryASinkHasNoUseForIsNotWaitedFor) {
    OtherNorthbound sparkplug;
    sparkplug.sink.good_only = true;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    counter(1, 1001);
    counter(2, 1002, Quality::stale);
    counter(3, 1003);
    run_for(10ms);
    reconnect();
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(50ms);
    EXPECT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 3}));
    acknowledge_all();
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
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

}  // namespace
}  // namespace eip2mqtt::app::history
