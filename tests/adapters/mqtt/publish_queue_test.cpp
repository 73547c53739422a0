#include "eip2mqtt/adapters/mqtt/publish_queue.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

Message msg(std::string topic, std::string payload, bool coalesce = true) {
    Message m;
    m.topic = std::move(topic);
    m.payload = std::move(payload);
    m.coalesce = coalesce;
    return m;
}

std::vector<std::string> drain(PublishQueue& q) {
    std::vector<std::string> out;
    while (auto m = q.pop()) {
        out.push_back(m->topic + "=" + m->payload);
    }
    return out;
}

TEST(PublishQueue, PopsInOrder) {
    PublishQueue q(10);
    EXPECT_TRUE(q.empty());
    EXPECT_FALSE(q.pop());
    q.push(msg("a", "1"));
    q.push(msg("b", "2"));
    q.push(msg("c", "3"));
    EXPECT_EQ(q.size(), 3u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"a=1", "b=2", "c=3"}));
    EXPECT_TRUE(q.empty());
}

TEST(PublishQueue, LatestValueReplacesInPlace) {
    PublishQueue q(10);
    q.push(msg("a", "1"));
    q.push(msg("b", "1"));
    q.push(msg("a", "2"));
    q.push(msg("a", "3"));
    EXPECT_EQ(q.size(), 2u);
    EXPECT_EQ(q.coalesced(), 2u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"a=3", "b=1"}));
}

TEST(PublishQueue, PoppedMessageIsNotReplaced) {
    PublishQueue q(10);
    q.push(msg("a", "1"));
    ASSERT_EQ(q.pop()->payload, "1");
    q.push(msg("a", "2"));
    EXPECT_EQ(q.coalesced(), 0u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"a=2"}));
}

TEST(PublishQueue, NonCoalescingMessagesAreEachKept) {
    PublishQueue q(10);
    q.push(msg("r", "1", false));
    q.push(msg("r", "2", false));
    q.push(msg("r", "3"));  // coalescing, but the queued ones do not coalesce
    EXPECT_EQ(q.coalesced(), 0u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"r=1", "r=2", "r=3"}));
}

TEST(PublishQueue, NewerValueDoesNotJumpAheadOfNonCoalescingOne) {
    PublishQueue q(10);
    q.push(msg("t", "1"));
    q.push(msg("t", "2", false));
    q.push(msg("t", "3"));
    // "3" must come last: replacing "1" in place would leave the topic at "2".
    EXPECT_EQ(drain(q), (std::vector<std::string>{"t=1", "t=2", "t=3"}));
}

TEST(PublishQueue, OverflowDropsOldestAndCounts) {
    PublishQueue q(3);
    for (int i = 0; i < 5; ++i) {
        q.push(msg("t" + std::to_string(i), std::to_string(i)));
    }
    EXPECT_EQ(q.size(), 3u);
    EXPECT_EQ(q.dropped_overflow(), 2u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"t2=2", "t3=3", "t4=4"}));
}

TEST(PublishQueue, CoalescingAfterOverflowStillFindsTheRightSlot) {
    PublishQueue q(2);
    q.push(msg("a", "1"));
    q.push(msg("b", "1"));
    q.push(msg("c", "1"));  // drops a
    q.push(msg("a", "2"));  // a is gone: queued anew, drops b
    q.push(msg("c", "2"));  // replaces c in place
    EXPECT_EQ(q.dropped_overflow(), 2u);
    EXPECT_EQ(q.coalesced(), 1u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"c=2", "a=2"}));
}

TEST(PublishQueue, ShrinkingCapacityDropsOldest) {
    PublishQueue q(5);
    for (int i = 0; i < 5; ++i) {
        q.push(msg("t" + std::to_string(i), "x"));
    }
    q.set_capacity(2);
    EXPECT_EQ(q.capacity(), 2u);
    EXPECT_EQ(q.dropped_overflow(), 3u);
    EXPECT_EQ(drain(q), (std::vector<std::string>{"t3=x", "t4=x"}));
}

TEST(PublishQueue, ZeroCapacityDropsEverything) {
    PublishQueue q(0);
    q.push(msg("a", "1"));
    EXPECT_TRUE(q.empty());
    EXPECT_EQ(q.dropped_overflow(), 1u);
}

TEST(PublishQueue, LongRunKeepsSequenceConsistent) {
    PublishQueue q(4);
    for (int round = 0; round < 1000; ++round) {
        q.push(msg("a", std::to_string(round)));
        q.push(msg("b", std::to_string(round)));
        if (round % 3 == 0) {
            q.pop();
        }
    }
    auto rest = drain(q);
    ASSERT_FALSE(rest.empty());
    EXPECT_LE(rest.size(), 2u);
    EXPECT_EQ(rest.back().substr(2), "999");
}

TEST(PublishQueue, LongTopicsKeepTheirKeysAcrossReplacementsAndPops) {
    // Topics longer than the small-string buffer live on the heap: the map's keys view them,
    // so a replaced or popped message must never leave a key dangling (ASan would see it).
    PublishQueue q(64);
    auto topic = [](int i) {
        return "acme/plant/turbine1/exchange/tag-number-" + std::to_string(i);
    };
    for (int round = 0; round < 200; ++round) {
        for (int i = 0; i < 20; ++i) q.push(msg(topic(i), std::to_string(round)));
        q.push(msg(topic(round % 20), "final-" + std::to_string(round), false));
        for (int i = 0; i < 7; ++i) q.pop();
    }
    EXPECT_LE(q.size(), 64u);
    const auto rest = drain(q);
    ASSERT_FALSE(rest.empty());
    EXPECT_TRUE(q.empty());
    q.push(msg(topic(1), "again"));
    q.push(msg(topic(1), "again2"));
    EXPECT_EQ(drain(q), (std::vector<std::string>{topic(1) + "=again2"}));
}

TEST(PublishQueue, ReleaseMemoryAfterABacklogDrained) {
    PublishQueue q(100000);
    for (int i = 0; i < 20000; ++i) q.push(msg("t/" + std::to_string(i), "1"));
    const auto peak_buckets = q.index_buckets_for_test();
    EXPECT_GE(peak_buckets, 20000u);
    q.release_memory();  // messages wait: nothing is released
    EXPECT_EQ(q.size(), 20000u);
    EXPECT_EQ(q.index_buckets_for_test(), peak_buckets);
    q.push(msg("t/0", "2"));  // the index still coalesces
    EXPECT_EQ(q.coalesced(), 1u);
    EXPECT_EQ(drain(q).front(), "t/0=2");
    EXPECT_EQ(q.index_buckets_for_test(), peak_buckets);  // drained, buckets kept
    q.release_memory();
    EXPECT_LT(q.index_buckets_for_test(), 100u);
    q.push(msg("a", "1"));
    q.push(msg("a", "2"));
    EXPECT_EQ(drain(q), (std::vector<std::string>{"a=2"}));
}

TEST(PublishQueue, PushLeavesWhatItDidNotKeepForReuse) {
    PublishQueue q(10);
    Message m = msg("plant/turbine1/e1/PRESSAO", "{\"value\":1}");
    q.push(std::move(m));
    EXPECT_TRUE(m.topic.empty());  // queued whole: nothing came back
    EXPECT_TRUE(m.payload.empty());

    m = msg("plant/turbine1/e1/PRESSAO", "{\"value\":2} and a payload too long for SSO");
    m.qos = 1;
    q.push(std::move(m));
    // Coalesced: the replaced payload's buffer and the topic's come back, blank.
    EXPECT_TRUE(m.topic.empty());
    EXPECT_TRUE(m.payload.empty());
    EXPECT_GE(m.topic.capacity(), std::string("plant/turbine1/e1/PRESSAO").size());
    EXPECT_EQ(m.qos, 0);
    EXPECT_EQ(drain(q),
              (std::vector<std::string>{
                  "plant/turbine1/e1/PRESSAO={\"value\":2} and a payload too long for SSO"}));
}

TEST(PublishQueue, CoalescesShortTopicsAcrossGrowth) {
    // Topics short enough to live inside their std::string move when the ring grows: the index
    // must follow them (ASan sees a stale view).
    PublishQueue q(1000);
    for (int i = 0; i < 100; ++i) q.push(msg("t" + std::to_string(i), "1"));
    for (int i = 0; i < 100; ++i) q.push(msg("t" + std::to_string(i), "2"));
    EXPECT_EQ(q.size(), 100u);
    EXPECT_EQ(q.coalesced(), 100u);
    const auto out = drain(q);
    ASSERT_EQ(out.size(), 100u);
    EXPECT_EQ(out.front(), "t0=2");
    EXPECT_EQ(out.back(), "t99=2");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
