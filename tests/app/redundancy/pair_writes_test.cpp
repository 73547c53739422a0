// The writes a standby left to the leader (docs/redundancy.md): each kept until the leader's
// answer is heard, matched by topic and correlation data, oldest first; the response topics to
// listen on follow what is kept; a takeover takes what was never answered, within the horizon.

#include "eip2mqtt/app/redundancy/pair_writes.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "eip2mqtt/core/redundancy/answer_key.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

class PairWritesTest : public ::testing::Test {
protected:
    /// A write to `acme/sp/SPEED_SP/set` of `value`, answered on `reply_topic` (the set topic's
    /// `/result` when empty) with `correlation`.
    static WriteRequest write(double value, std::string reply_topic = "",
                              std::string correlation = "") {
        const std::string target = "acme/sp/SPEED_SP/set";
        if (reply_topic.empty()) reply_topic = target + "/result";
        return {{std::move(reply_topic), std::move(correlation)},
                target,
                ExchangeWrite{nullptr, {{0, core::plan::Value{value}}}},
                {}};
    }
    static adapters::mqtt::Incoming answer(std::string topic, std::string correlation = "") {
        adapters::mqtt::Incoming incoming;
        incoming.topic = std::move(topic);
        incoming.payload = R"({"ok":true})";
        incoming.correlation_data = std::move(correlation);
        return incoming;
    }
    static double value_of(const WriteRequest& request) {
        return std::get<double>(std::get<ExchangeWrite>(request.outcome).writes[0].value);
    }

    core::MonoTime t0_{std::chrono::seconds(100)};
    int topics_changed_ = 0;
    PairWrites writes_{10s, [this] { ++topics_changed_; }};
};

TEST_F(PairWritesTest, AnAnswerHeardTakesTheOldestWriteOfItsTopic) {
    writes_.leave(write(1), t0_);
    writes_.leave(write(2), t0_ + 1ms);
    writes_.heard(answer("acme/sp/SPEED_SP/set/result"));
    EXPECT_EQ(writes_.counters().answers_heard, 1u);
    const auto unanswered = writes_.take_unanswered(t0_ + 2ms, {}).unanswered;
    ASSERT_EQ(unanswered.size(), 1u);
    EXPECT_EQ(value_of(unanswered[0]), 2.0);
}

TEST_F(PairWritesTest, CorrelationDataTellsWritesOnOneResponseTopicApart) {
    writes_.leave(write(1, "client/replies", "a"), t0_);
    writes_.leave(write(2, "client/replies", "b"), t0_);
    writes_.heard(answer("client/replies", "b"));
    writes_.heard(answer("client/replies", "c"));  // no write of ours: ignored
    writes_.heard(answer("elsewhere", "a"));
    const auto unanswered = writes_.take_unanswered(t0_, {}).unanswered;
    ASSERT_EQ(unanswered.size(), 1u);
    EXPECT_EQ(value_of(unanswered[0]), 1.0);
    EXPECT_EQ(writes_.counters().answers_heard, 1u);
}

TEST_F(PairWritesTest, ResponseTopicsAreListenedToWhileAWriteWaitsThere) {
    writes_.leave(write(1), t0_);  // `{set}/result`: under the result filters already
    EXPECT_TRUE(writes_.response_topics().empty());
    EXPECT_EQ(topics_changed_, 0);
    writes_.leave(write(2, "client/replies", "a"), t0_);
    writes_.leave(write(3, "client/replies", "b"), t0_);
    EXPECT_EQ(writes_.response_topics(), std::vector<std::string>{"client/replies"});
    EXPECT_EQ(topics_changed_, 1);
    writes_.heard(answer("client/replies", "a"));
    EXPECT_EQ(topics_changed_, 1);  // one write still waits there
    writes_.heard(answer("client/replies", "b"));
    // Still listened to, for the next write's answer (below).
    EXPECT_EQ(writes_.response_topics(), std::vector<std::string>{"client/replies"});
    EXPECT_EQ(topics_changed_, 1);
}

// One client writing every 250 ms with one response topic, the leader answering each within
// milliseconds: a subscription dropped with each answer and asked again with the next write
// reached the broker after the leader's answer now and then, and the unit taking the lead
// refused `standby` a write the leader had answered `ok`.
TEST_F(PairWritesTest, AResponseTopicStaysListenedToBetweenOneWritesAnswerAndTheNextWrite) {
    for (int i = 0; i < 8; ++i) {
        const auto correlation = "w" + std::to_string(i);
        writes_.leave(write(i, "answers/chaos", correlation), t0_ + i * 250ms);
        writes_.heard(answer("answers/chaos", correlation));
        EXPECT_EQ(writes_.response_topics(), std::vector<std::string>{"answers/chaos"});
    }
    EXPECT_EQ(topics_changed_, 1);  // subscribed once, before the first answer could come
    EXPECT_EQ(writes_.counters().answers_heard, 8u);
    EXPECT_TRUE(writes_.take_unanswered(t0_ + 2s, {}).unanswered.empty());
}

TEST_F(PairWritesTest, AResponseTopicLapsesAfterTheLingerAndTheBoundKeepsTheLatest) {
    writes_.leave(write(1, "client/replies", "a"), t0_);
    writes_.heard(answer("client/replies", "a"));
    writes_.leave(write(2), t0_ + PairWrites::topic_linger);
    EXPECT_EQ(writes_.response_topics(), std::vector<std::string>{"client/replies"});
    writes_.leave(write(3), t0_ + PairWrites::topic_linger + 1ms);
    EXPECT_TRUE(writes_.response_topics().empty());
    EXPECT_EQ(topics_changed_, 2);
    for (std::size_t i = 0; i <= PairWrites::max_topics; ++i) {
        writes_.leave(write(1, "replies/" + std::to_string(i + 100)), t0_ + 11min + i * 1ms);
    }
    const auto topics = writes_.response_topics();
    EXPECT_EQ(topics.size(), PairWrites::max_topics);
    EXPECT_EQ(topics.front(), "replies/101");  // the least recent one went
    EXPECT_EQ(topics.back(), "replies/" + std::to_string(PairWrites::max_topics + 100));
}

TEST_F(PairWritesTest, AWriteItsNorthboundRefusedIsNotKept) {
    auto invalid = write(1);
    invalid.outcome = core::write::WriteRejection{core::write::WriteError::read_only, "read-only"};
    writes_.leave(std::move(invalid), t0_);
    EXPECT_EQ(writes_.size(), 0u);
}

TEST_F(PairWritesTest, ATakeoverTakesOnlyWritesWithinTheHorizonAndKeepsNone) {
    writes_.leave(write(1, "client/replies"), t0_);
    writes_.leave(write(2), t0_ + 5s);
    EXPECT_EQ(topics_changed_, 1);
    const auto unanswered = writes_.take_unanswered(t0_ + 12s, {}).unanswered;
    ASSERT_EQ(unanswered.size(), 1u);
    EXPECT_EQ(value_of(unanswered[0]), 2.0);
    EXPECT_EQ(writes_.counters().forgotten, 1u);
    EXPECT_EQ(writes_.size(), 0u);
    EXPECT_TRUE(writes_.response_topics().empty());
    EXPECT_EQ(topics_changed_, 2);  // the forgotten write's response topic is left
    EXPECT_TRUE(writes_.take_unanswered(t0_ + 12s, {}).unanswered.empty());
}

TEST_F(PairWritesTest, TheBoundForgetsTheOldest) {
    for (std::size_t i = 0; i <= PairWrites::max_left; ++i) {
        writes_.leave(write(static_cast<double>(i)), t0_);
    }
    EXPECT_EQ(writes_.size(), PairWrites::max_left);
    EXPECT_EQ(writes_.counters().forgotten, 1u);
    EXPECT_EQ(value_of(writes_.take_unanswered(t0_, {}).unanswered.front()), 1.0);
}

TEST_F(PairWritesTest, WritesTheOldLeadersImagesListAsAnsweredAreNotSettledAgainButAnswered) {
    // Left unheard: the answers went while this unit's connection was down, or before its
    // subscription to a new response topic reached the broker, or never (the leader died
    // after the broker took the image listing them, before its answer left).
    using core::redundancy::ListedResult;
    writes_.leave(write(1, "client/replies", "a"), t0_);
    writes_.leave(write(2, "client/replies", "b"), t0_);
    writes_.leave(write(3), t0_);
    writes_.leave(write(4), t0_);
    writes_.leave(write(5, "client/replies", "d"), t0_);
    const std::vector<core::redundancy::ListedAnswer> listed{
        {core::redundancy::answer_key("client/replies", "b"), ListedResult::ok},
        {core::redundancy::answer_key("acme/sp/SPEED_SP/set/result", ""), ListedResult::refused},
        {core::redundancy::answer_key("client/replies", "c"), ListedResult::ok},
        {core::redundancy::answer_key("client/replies", "d"), ListedResult::unknown}};
    const auto taken = writes_.take_unanswered(t0_ + 1ms, listed);
    // One listing of a key shared by two writes (no correlation data) takes one of them.
    ASSERT_EQ(taken.unanswered.size(), 2u);
    EXPECT_EQ(value_of(taken.unanswered[0]), 1.0);
    EXPECT_EQ(value_of(taken.unanswered[1]), 4.0);
    ASSERT_EQ(taken.listed.size(), 3u);
    EXPECT_EQ(value_of(taken.listed[0].request), 2.0);
    EXPECT_EQ(taken.listed[0].result, ListedResult::ok);
    EXPECT_EQ(value_of(taken.listed[1].request), 3.0);
    EXPECT_EQ(taken.listed[1].result, ListedResult::refused);
    EXPECT_EQ(taken.listed[2].result, ListedResult::unknown);
    EXPECT_EQ(writes_.counters().answers_listed, 3u);
    EXPECT_EQ(writes_.counters().answers_repeated, 2u) << "an older release's listing is not";
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
