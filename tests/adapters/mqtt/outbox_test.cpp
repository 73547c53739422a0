// The client's outbox without a broker: two lanes served in turn, buffers handed back
// to the publisher, a bounded stock of spares, and memory given back after a drained backlog.

#include "adapters/mqtt/detail/outbox.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

Message message(std::string topic, std::string payload, bool batch = false) {
    Message m;
    m.topic = std::move(topic);
    m.payload = std::move(payload);
    m.batch_lane = batch;
    return m;
}

/// Takes everything, checking that peek_next always shows what take_next then takes (the
/// client decides by it whether the next publication needs room for an acknowledgement).
std::vector<std::string> drain(Outbox& outbox) {
    std::vector<std::string> topics;
    Message next;
    for (const Message* peeked = outbox.peek_next(); peeked != nullptr;
         peeked = outbox.peek_next()) {
        const std::string expected = peeked->topic;
        EXPECT_TRUE(outbox.take_next(next));
        EXPECT_EQ(next.topic, expected);
        topics.push_back(next.topic);
    }
    EXPECT_FALSE(outbox.take_next(next));
    return topics;
}

TEST(Outbox, BothLanesAreServedInTurnSoNeitherStarvesTheOther) {
    Outbox outbox(100, 100);
    for (const auto* topic : {"t/1", "t/2", "t/3"}) {
        auto m = message(topic, "1");
        outbox.push(m);
    }
    for (const auto* topic : {"t/_values/1", "t/_values/2"}) {
        auto m = message(topic, "{}", true);
        outbox.push(m);
    }
    EXPECT_EQ(outbox.size(), 5u);
    EXPECT_EQ(drain(outbox),
              (std::vector<std::string>{"t/1", "t/_values/1", "t/2", "t/_values/2", "t/3"}));
    EXPECT_TRUE(outbox.empty());
}

TEST(Outbox, TheBatchLaneGoesFirstWhenAskedAndTheTagLaneGetsWhatIsLeft) {
    Outbox outbox(100, 100, true);
    for (const auto* topic : {"t/1", "t/2"}) {
        auto m = message(topic, "1");
        outbox.push(m);
    }
    for (const auto* topic : {"t/_values/1", "t/_values/2"}) {
        auto m = message(topic, "{}", true);
        outbox.push(m);
    }
    EXPECT_EQ(drain(outbox),
              (std::vector<std::string>{"t/_values/1", "t/_values/2", "t/1", "t/2"}));
}

TEST(Outbox, BatchFirstSetOnAQueueAlreadyWaitingAppliesFromTheNextTake) {
    // A reload's mqtt.batch_first: set on the running client, not only at its start.
    Outbox outbox(100, 100);
    for (const auto* topic : {"t/1", "t/2", "t/3"}) {
        auto m = message(topic, "1");
        outbox.push(m);
    }
    for (const auto* topic : {"t/_values/1", "t/_values/2"}) {
        auto m = message(topic, "{}", true);
        outbox.push(m);
    }
    Message next;
    ASSERT_TRUE(outbox.take_next(next));
    EXPECT_EQ(next.topic, "t/1");
    outbox.set_batch_first(true);
    EXPECT_EQ(drain(outbox),
              (std::vector<std::string>{"t/_values/1", "t/_values/2", "t/2", "t/3"}));
}

TEST(Outbox, DiscardAllEmptiesBothLanes) {
    Outbox outbox(100, 100);
    for (const bool batch : {false, true, false}) {
        auto m = message(batch ? "t/_values" : "t/1", "1", batch);
        m.coalesce = false;
        outbox.push(m);
    }
    EXPECT_EQ(outbox.discard_all(), 3u);
    EXPECT_TRUE(outbox.empty());
    EXPECT_TRUE(drain(outbox).empty());
}

TEST(Outbox, APushQueuedWholeGetsASpareBackAndACoalescedOneTheBuffersItReplaced) {
    Outbox outbox(100, 100);
    const std::string long_payload(200, 'x');
    outbox.recycle(message(std::string(100, 's'), long_payload), 8);  // a spare with buffers

    auto first = message("t/1", long_payload);
    outbox.push(first);  // queued whole: the spare comes back, blank, with its buffers
    EXPECT_TRUE(first.topic.empty());
    EXPECT_GE(first.payload.capacity(), long_payload.size());

    first.topic = "t/1";
    first.payload = "2";
    outbox.push(first);  // replaces the queued t/1: its buffers come back
    EXPECT_TRUE(first.payload.empty());
    EXPECT_GE(first.payload.capacity(), long_payload.size());
    EXPECT_EQ(outbox.tags().coalesced(), 1u);
    EXPECT_EQ(outbox.size(), 1u);
}

TEST(Outbox, SparesAreKeptUpToTheWindowAndComeBackBlank) {
    Outbox outbox(100, 100);
    const std::string long_topic(100, 't');
    for (int i = 0; i < 5; ++i) outbox.recycle(message(long_topic, "v"), 2);
    int spares = 0;
    for (int i = 0; i < 5; ++i) {
        Message m;  // queued whole, with no buffers of its own
        m.topic = "n/" + std::to_string(i);
        outbox.push(m);
        EXPECT_TRUE(m.topic.empty());
        EXPECT_TRUE(m.payload.empty());
        if (m.topic.capacity() >= long_topic.size()) ++spares;
    }
    EXPECT_EQ(spares, 2);  // the other three were freed
    EXPECT_EQ(outbox.size(), 5u);
}

TEST(Outbox, MemoryIsGivenBackOnlyOnceABacklogPastTheThresholdHasDrained) {
    Outbox outbox(1000, 100);
    for (int i = 0; i < 50; ++i) {
        auto m = message("t/" + std::to_string(i), "v");
        outbox.push(m);
    }
    EXPECT_FALSE(outbox.release_after_backlog(50));  // not drained yet
    drain(outbox);
    EXPECT_FALSE(outbox.release_after_backlog(51));  // the backlog stayed below it
    EXPECT_TRUE(outbox.release_after_backlog(50));
    EXPECT_FALSE(outbox.release_after_backlog(50));  // once per backlog
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
