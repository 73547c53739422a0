// One northbound's way through the store-and-forward journal: its rate, its window of
// unacknowledged entries, the rewind of dropped ones, and entries it published live.

#include "eip2mqtt/app/history/sink_replay.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "tests/support/fakes/recording_history_sink.hpp"

namespace eip2mqtt::app::history {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const core::MonoTime t0{std::chrono::hours(1)};

class SinkReplayTest : public testing::Test {
protected:
    test::RecordingHistorySink sink_;
    bool connected_ = true;
    std::uint64_t backlog_ = 0;
    SinkReplay replay_{sink_,
                       LinkProbe{[this] { return connected_; }, [this] { return backlog_; }}};
};

TEST_F(SinkReplayTest, TheRateAllowsEntriesUpToATenthOfASecondsWorth) {
    replay_.start(t0, false);
    EXPECT_TRUE(replay_.active());
    EXPECT_EQ(replay_.room(t0, 100), 0u);
    EXPECT_EQ(replay_.room(t0 + 62500us, 100), 6u);
    EXPECT_EQ(replay_.room(t0 + 10s, 100), 10u);  // capped at rate / 10
    for (std::uint64_t id = 1; id <= 10; ++id) replay_.handed(id, false);
    EXPECT_EQ(replay_.cursor(), 10u);
    EXPECT_EQ(replay_.room(t0 + 10s, 100), 0u);
    EXPECT_EQ(replay_.room(t0 + 11s, 0.5), 0u);
    EXPECT_EQ(replay_.room(t0 + 14s, 0.5), 1u);  // a slow rate allows one entry at a time
}

TEST_F(SinkReplayTest, NoRoomWhileDisconnectedOrWhileLiveDataQueues) {
    replay_.start(t0, false);
    connected_ = false;
    EXPECT_EQ(replay_.room(t0 + 1s, 100), 0u);
    connected_ = true;
    backlog_ = 1001;
    EXPECT_EQ(replay_.room(t0 + 2s, 100), 0u);
    backlog_ = 1000;
    EXPECT_EQ(replay_.room(t0 + 3s, 100), 10u);
}

TEST_F(SinkReplayTest, AcknowledgementsMoveWhatIsDeliveredThrough) {
    replay_.start(t0, false);
    for (std::uint64_t id = 1; id <= 3; ++id) replay_.handed(id, true);
    EXPECT_EQ(replay_.outstanding(), 3u);
    EXPECT_EQ(replay_.through(), 0u);
    EXPECT_TRUE(replay_.acknowledge(2));
    EXPECT_EQ(replay_.through(), 0u);
    EXPECT_TRUE(replay_.acknowledge(1));
    EXPECT_EQ(replay_.through(), 2u);
    EXPECT_FALSE(replay_.acknowledge(1));
    EXPECT_TRUE(replay_.acknowledge(3));
    EXPECT_EQ(replay_.through(), 3u);
}

TEST_F(SinkReplayTest, EntriesTheClientDroppedGoAgainAfterTwoIdleTicks) {
    replay_.start(t0, false);
    replay_.handed(1, true);
    replay_.handed(2, true);
    backlog_ = 2;
    EXPECT_EQ(replay_.room(t0 + 1s, 100), 10u);
    backlog_ = 0;  // the client holds none of them
    EXPECT_EQ(replay_.room(t0 + 2s, 100), 0u);
    EXPECT_EQ(replay_.outstanding(), 2u);
    EXPECT_EQ(replay_.room(t0 + 3s, 100), 0u);
    EXPECT_EQ(replay_.outstanding(), 0u);
    EXPECT_EQ(replay_.cursor(), 0u);
    EXPECT_FALSE(replay_.acknowledge(1));
}

TEST_F(SinkReplayTest, AStartThatRewindsForgetsWhatWentWithTheLastConnection) {
    replay_.start(t0, false);
    replay_.handed(4, false);
    replay_.handed(5, true);
    replay_.handed(6, true);
    replay_.start(t0 + 1s, true);
    EXPECT_EQ(replay_.cursor(), 4u);
    EXPECT_EQ(replay_.outstanding(), 0u);
}

TEST_F(SinkReplayTest, EntriesJournaledWhileConnectedBetweenReplaysCountAsDelivered) {
    replay_.note_live(t0, 5);
    replay_.note_live(t0 + 1s, 7);
    EXPECT_EQ(replay_.cursor(), 0u);  // within the grace
    replay_.note_live(t0 + 2s, 8);
    EXPECT_EQ(replay_.cursor(), 5u);
    connected_ = false;  // the connection went: what was journaled since is not delivered
    replay_.note_live(t0 + 3s, 9);
    connected_ = true;
    replay_.note_live(t0 + 4s, 10);
    replay_.note_live(t0 + 5s, 11);
    EXPECT_EQ(replay_.cursor(), 5u);
    replay_.note_live(t0 + 6s, 12);
    EXPECT_EQ(replay_.cursor(), 10u);
}

TEST_F(SinkReplayTest, NothingCountsAsLiveDuringAReplay) {
    replay_.start(t0, false);
    replay_.note_live(t0, 5);
    replay_.note_live(t0 + 3s, 6);
    EXPECT_EQ(replay_.cursor(), 0u);
    replay_.finish();
    EXPECT_FALSE(replay_.active());
}

TEST_F(SinkReplayTest, APaceOfTwiceWhatATickThatRanOutOfTimeHanded) {
    EXPECT_EQ(replay_.pace(), SIZE_MAX);
    replay_.paced(3, true);
    EXPECT_EQ(replay_.pace(), 6u);
    replay_.paced(0, true);
    EXPECT_EQ(replay_.pace(), 1u);
    replay_.paced(3, false);
    EXPECT_EQ(replay_.pace(), SIZE_MAX);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::history
