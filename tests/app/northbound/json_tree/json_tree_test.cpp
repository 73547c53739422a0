// The JSON topic tree as a northbound: the domain events the exchanges report become
// today's topics and payloads (docs/mqtt-api.md), and a message on a `set` topic comes back as one
// decoded write whose answer goes to this northbound.

#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "eip2mqtt/app/northbound/json_tree/json_tree_meta.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::quality::Quality;

core::plan::ExchangePlan plan(std::string name, core::plan::Direction direction) {
    using core::plan::TagType;
    return test::test_plan(
        name, direction, 8,
        {test::test_tag("A", 0, TagType::dint, true), test::test_tag("B", 4, TagType::dint, true)},
        "t1/" + name);
}

class JsonTreeTest : public ::testing::Test {
protected:
    explicit JsonTreeTest(PublishSettings settings = {}) : uns_(settings, {}, "acme") {
        uns_.northbound().exchanges_changed({{&consumed_}, {&produced_}}, {});
        uns_.northbound().republish_meta();  // connected
        uns_.northbound().publish_due_meta();
        // Each exchange's `_meta` (JsonTreeMetaTest); the tests below start after them.
        EXPECT_EQ(published().size(), 2u);
        uns_.publisher.published.clear();
    }
    const std::vector<adapters::mqtt::Message>& published() const {
        return uns_.publisher.published;
    }

    /// A and B of the consumed exchange, as the sample of the datagram of request id 7.
    void named_sample() {
        uns_.northbound().tag_samples(
            {consumed_, Quality::good, 1000, false, two_samples_, core::redundancy::SampleKey{7}});
    }

    const std::vector<TagSample> two_samples_{{0, core::plan::Value{std::int64_t{1}}},
                                              {1, core::plan::Value{std::int64_t{2}}}};
    core::plan::ExchangePlan consumed_ = plan("in", core::plan::Direction::consume);
    core::plan::ExchangePlan produced_ = plan("out", core::plan::Direction::produce);
    test::JsonTreeRecorder uns_;
};

TEST_F(JsonTreeTest, EachSampleIsOneRetainedTagTopicWithValueTimestampAndQuality) {
    const std::vector<TagSample> samples{{1, core::plan::Value{std::int64_t{-5}}}};
    uns_.northbound().tag_samples({consumed_, Quality::stale, 1700000000123, false, samples});
    ASSERT_EQ(published().size(), 1u);
    const auto& m = published()[0];
    EXPECT_EQ(m.topic, "acme/t1/in/B");
    EXPECT_EQ(m.payload, R"({"value":-5,"timestamp":1700000000123,"quality":"stale"})");
    EXPECT_EQ(m.qos, 1);
    EXPECT_TRUE(m.retain);
    EXPECT_TRUE(m.coalesce);  // the latest value wins while queued
}

class JsonTreeBatchTest : public JsonTreeTest {
protected:
    JsonTreeBatchTest()
        : JsonTreeTest(PublishSettings{0, false, core::config::PayloadFormat::raw, true}) {}
};

TEST_F(JsonTreeBatchTest, AConsumedBatchAddsOneValuesMessageTheEchoOfAProducedOneDoesNot) {
    const std::vector<TagSample> samples{{0, core::plan::Value{std::int64_t{1}}},
                                         {1, core::plan::Value{std::int64_t{2}}}};
    uns_.northbound().tag_samples({consumed_, Quality::good, 1000, false, samples});
    ASSERT_EQ(published().size(), 3u);
    EXPECT_EQ(published()[0].payload, "1");  // payload: raw
    EXPECT_EQ(published()[0].qos, 0);
    EXPECT_FALSE(published()[0].retain);
    const auto& values = published()[2];
    EXPECT_EQ(values.topic, "acme/t1/in/_values");
    EXPECT_EQ(values.payload, R"({"timestamp":1000,"quality":"good","values":{"A":1,"B":2}})");
    EXPECT_TRUE(values.batch_lane);
    EXPECT_FALSE(values.coalesce);  // history: every one is delivered

    uns_.northbound().tag_samples({produced_, Quality::good, 1000, false, samples});
    EXPECT_EQ(published().size(), 5u);
    EXPECT_EQ(uns_.publisher.on("acme/t1/out/_values").size(), 0u);
}

TEST_F(JsonTreeBatchTest, WithAPairEachNamedSampleOnValuesCarriesItsTokenAndARepublishIsNot) {
    std::vector<core::redundancy::SampleKey> asked;
    uns_.northbound().set_sample_tokens([&](const SampleBatch& batch) {
        asked.push_back(*batch.key);
        return std::uint64_t{100 + asked.size()};
    });
    named_sample();
    ASSERT_EQ(published().size(), 3u);
    EXPECT_EQ(published()[0].ack_token, 0u);
    EXPECT_EQ(published()[1].ack_token, 0u);
    EXPECT_EQ(published()[2].topic, "acme/t1/in/_values");
    EXPECT_EQ(published()[2].ack_token, 101u);
    EXPECT_EQ(asked, std::vector<core::redundancy::SampleKey>{{7}});
    // A refresh names no sample; a republish (a takeover) leaves `_values` to `_history`.
    uns_.northbound().tag_samples({consumed_, Quality::good, 1000, false, two_samples_});
    EXPECT_EQ(published().back().ack_token, 0u);
    uns_.northbound().tag_samples({consumed_, Quality::good, 1000, true, two_samples_});
    EXPECT_EQ(uns_.publisher.on("acme/t1/in/_values").size(), 2u);
    EXPECT_EQ(asked.size(), 1u);
}

TEST_F(JsonTreeTest, WithAPairAndNoBatchTheLastTagTopicOfASampleCarriesItsToken) {
    uns_.northbound().set_sample_tokens([](const SampleBatch&) { return std::uint64_t{42}; });
    named_sample();
    ASSERT_EQ(published().size(), 2u);
    EXPECT_EQ(published()[0].ack_token, 0u);
    EXPECT_EQ(published()[1].ack_token, 42u);
}

TEST_F(JsonTreeTest, WriteResultsGoToTheReplyTopicOnceEachAndNowhereWithoutOne) {
    uns_.northbound().write_result({"r/1", "c1", nullptr}, std::nullopt);
    uns_.northbound().write_result({"r/2", "", nullptr}, "queue full");
    uns_.northbound().write_result({"", "c3", nullptr}, "unknown tag");
    ASSERT_EQ(published().size(), 2u);
    EXPECT_EQ(published()[0].topic, "r/1");
    EXPECT_EQ(published()[0].payload, R"({"ok":true})");
    EXPECT_EQ(published()[0].correlation_data, "c1");
    EXPECT_EQ(published()[0].qos, 1);
    EXPECT_FALSE(published()[0].retain);
    EXPECT_FALSE(published()[0].coalesce);
    EXPECT_EQ(published()[1].payload, R"({"error":"queue full","ok":false})");
}

TEST_F(JsonTreeTest, ChangedExchangesClearRetiredTopicsAndSubscribeToTheSetTopics) {
    EXPECT_EQ(uns_.publisher.subscriptions,
              (std::vector<std::string>{"acme/+/+/set", "acme/+/+/+/set"}));
    const std::vector<std::string> retired{"acme/t1/gone/A", "acme/t1/gone/_status"};
    uns_.northbound().exchanges_changed({{}, {&produced_}}, retired);
    EXPECT_TRUE(published().empty());  // in slices, by publish_changes
    EXPECT_FALSE(uns_.northbound().publish_changes(1000));
    ASSERT_EQ(published().size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(published()[i].topic, retired[i]);
        EXPECT_EQ(published()[i].payload, "");  // an empty retained message clears the topic
        EXPECT_TRUE(published()[i].retain);
    }
    // The consumed exchange is gone: its `set` topic is no longer ours.
    uns_.northbound().on_message({"acme/t1/in/A/set", "1", false, "", "", -1});
    EXPECT_TRUE(uns_.writes.empty());
}

TEST_F(JsonTreeTest, APairsUnitListensWhereWritesAreAnsweredAndHearsWhatIsNoWrite) {
    std::vector<std::string> heard;
    std::vector<std::string> response_topics;
    uns_.northbound().set_answer_listener(
        [&](const adapters::mqtt::Incoming& answer) { heard.push_back(answer.topic); },
        [&] { return response_topics; });
    EXPECT_EQ(uns_.publisher.subscriptions,
              (std::vector<std::string>{"acme/+/+/set", "acme/+/+/+/set", "acme/+/+/set/result",
                                        "acme/+/+/+/set/result"}));
    response_topics = {"client/replies"};
    uns_.northbound().listen_again();
    EXPECT_EQ(uns_.publisher.subscriptions.back(), "client/replies");
    // The set filters follow the running exchanges, and their results with them.
    uns_.northbound().exchanges_changed({{}, {&produced_}}, {});
    EXPECT_EQ(uns_.publisher.subscriptions,
              (std::vector<std::string>{"acme/+/+/set", "acme/+/+/+/set", "acme/+/+/set/result",
                                        "acme/+/+/+/set/result", "client/replies"}));
    uns_.northbound().on_message({"acme/t1/out/A/set/result", R"({"ok":true})", false, "", "", -1});
    uns_.northbound().on_message({"client/replies", R"({"ok":true})", false, "", "c", -1});
    uns_.northbound().on_message({"acme/t1/out/A/set", "5", false, "", "", -1});
    EXPECT_EQ(heard, (std::vector<std::string>{"acme/t1/out/A/set/result", "client/replies"}));
    EXPECT_EQ(uns_.writes.size(), 1u);  // the write is a write, not an answer
}

TEST_F(JsonTreeTest, ASetMessageBecomesOneWriteRequestAnsweredByThisNorthbound) {
    uns_.northbound().on_message({"acme/t1/out/set", R"({"A":5,"B":6})", false, "", "id", -1});
    ASSERT_EQ(uns_.writes.size(), 1u);
    const auto& request = uns_.writes[0];
    EXPECT_EQ(request.reply.origin, &uns_.northbound());
    EXPECT_EQ(request.reply.topic, "acme/t1/out/set/result");
    EXPECT_EQ(request.reply.correlation_data, "id");
    EXPECT_EQ(request.target, "acme/t1/out/set");
    const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
    ASSERT_NE(write, nullptr);
    EXPECT_EQ(write->producer, &produced_);  // its handle: the running exchange's plan
    ASSERT_EQ(write->writes.size(), 2u);
    EXPECT_EQ(write->writes[1].tag_index, 1u);
}

TEST_F(JsonTreeTest, ARefusedSetMessageIsHandedOnAsARejectionWithTheReasonForTheLog) {
    uns_.northbound().on_message({"acme/t1/out/A/set", "1", false, "acme/t1/out/A", "", -1});
    uns_.northbound().on_message({"acme/t1/in/A/set", "1", false, "", "", -1});
    uns_.northbound().on_message({"acme/t1/out/A", "1", false, "", "", -1});  // not a set topic
    ASSERT_EQ(uns_.writes.size(), 2u);
    const auto* bad_topic = std::get_if<core::write::WriteRejection>(&uns_.writes[0].outcome);
    ASSERT_NE(bad_topic, nullptr);
    EXPECT_EQ(bad_topic->error, core::write::WriteError::bad_response_topic);
    EXPECT_NE(uns_.writes[0].log_detail.find("answered on acme/t1/out/A/set/result"),
              std::string::npos)
        << uns_.writes[0].log_detail;
    const auto* read_only = std::get_if<core::write::WriteRejection>(&uns_.writes[1].outcome);
    ASSERT_NE(read_only, nullptr);
    EXPECT_EQ(read_only->error, core::write::WriteError::read_only);
    EXPECT_TRUE(published().empty());  // answering is the WriteHandler's call
}

TEST(JsonTreeMetaTest, PublishedOnConnectingThenOnlyWhenAReloadChangesItAndAgainOnReconnect) {
    test::JsonTreeRecorder uns;
    auto in = plan("in", core::plan::Direction::consume);
    const auto out = plan("out", core::plan::Direction::produce);
    uns.northbound().exchanges_changed({{&in}, {&out}}, {});
    const auto& published = uns.publisher.published;
    EXPECT_TRUE(published.empty());  // not connected yet: the connection publishes them
    in.spec.period = std::chrono::milliseconds(500);  // a reload before the first connection
    uns.northbound().exchanges_changed({{&in}, {&out}}, {});
    EXPECT_TRUE(published.empty());
    uns.northbound().republish_meta();  // connected
    uns.northbound().publish_due_meta();
    ASSERT_EQ(published.size(), 2u);
    EXPECT_NE(published[0].payload.find(R"("period_ms":500)"), std::string::npos);
    EXPECT_EQ(published[0].topic, "acme/t1/in/_meta");
    EXPECT_EQ(published[1].topic, "acme/t1/out/_meta");
    for (const auto& m : published) {
        EXPECT_TRUE(m.retain) << m.topic;
        EXPECT_NE(m.payload.find(R"("tags":{"A":)"), std::string::npos) << m.payload;
    }

    uns.northbound().exchanges_changed({{&in}, {&out}}, {});  // a reload that kept both
    uns.northbound().publish_changes(1000);
    EXPECT_EQ(published.size(), 2u);

    in.spec.period = std::chrono::milliseconds(250);  // a reload that changed one
    uns.northbound().exchanges_changed({{&in}, {&out}}, {});
    uns.northbound().publish_changes(1000);
    ASSERT_EQ(published.size(), 3u);
    EXPECT_EQ(published[2].topic, "acme/t1/in/_meta");
    EXPECT_NE(published[2].payload.find(R"("period_ms":250)"), std::string::npos);

    // Removed (diff_plans clears its topic), then back: published again.
    uns.northbound().exchanges_changed({{}, {&out}}, {});
    uns.northbound().publish_changes(1000);
    uns.northbound().exchanges_changed({{&in}, {&out}}, {});
    uns.northbound().publish_changes(1000);
    ASSERT_EQ(published.size(), 4u);
    EXPECT_EQ(published[3].topic, "acme/t1/in/_meta");

    uns.northbound().republish_meta();
    uns.northbound().publish_due_meta();
    ASSERT_EQ(published.size(), 6u);
    // Formatted again from the running plans: what the broker was last given.
    for (std::size_t i = 4; i < 6; ++i) {
        const auto& described = published[i].topic == "acme/t1/in/_meta" ? in : out;
        EXPECT_EQ(published[i].payload, format_meta_payload(described)) << published[i].topic;
    }
}

TEST(JsonTreeMetaTest, AReloadPublishesInSlicesClearsFirstThenChangedDescriptions) {
    test::JsonTreeRecorder uns;
    auto in = plan("in", core::plan::Direction::consume);
    const auto out = plan("out", core::plan::Direction::produce);
    uns.northbound().exchanges_changed({{&in}, {&out}}, {});
    uns.northbound().republish_meta();  // connected
    uns.northbound().publish_due_meta();
    const auto& published = uns.publisher.published;
    ASSERT_EQ(published.size(), 2u);

    // A reload that retires five topics and changes `in` (two tags: 3 units to describe).
    in.spec.period = std::chrono::milliseconds(250);
    const std::vector<std::string> retired{"acme/a", "acme/b", "acme/c", "acme/d", "acme/e"};
    uns.northbound().exchanges_changed({{&in}, {&out}}, retired);
    EXPECT_EQ(published.size(), 2u);  // nothing yet: the subscriptions only
    EXPECT_TRUE(uns.northbound().changes_pending());
    EXPECT_TRUE(uns.northbound().publish_changes(2));
    EXPECT_TRUE(uns.northbound().publish_changes(2));
    ASSERT_EQ(published.size(), 6u);
    // The last clear, then a description begun with the unit left takes its whole cost.
    EXPECT_TRUE(uns.northbound().publish_changes(2));
    ASSERT_EQ(published.size(), 8u);
    for (std::size_t i = 0; i < retired.size(); ++i) {
        EXPECT_EQ(published[2 + i].topic, retired[i]);
        EXPECT_EQ(published[2 + i].payload, "");
        EXPECT_TRUE(published[2 + i].retain);
    }
    EXPECT_EQ(published[7].topic, "acme/t1/in/_meta");
    // `out` is compared, unchanged: nothing published, nothing left.
    EXPECT_FALSE(uns.northbound().publish_changes(2));
    EXPECT_EQ(published.size(), 8u);
    EXPECT_FALSE(uns.northbound().changes_pending());
}

TEST(JsonTreeMetaTest, AReconnectSendsTheDescriptionsAFewAtATimeInConfigurationOrder) {
    test::JsonTreeRecorder uns;
    constexpr std::size_t per_call = JsonTree::meta_per_call;
    std::vector<core::plan::ExchangePlan> plans;
    for (std::size_t i = 0; i < 2 * per_call + 1; ++i) {
        plans.push_back(plan("e" + std::to_string(i), core::plan::Direction::consume));
    }
    ExchangeSet running;
    for (const auto& p : plans) running.consumed.push_back(&p);
    uns.northbound().exchanges_changed(running, {});
    uns.northbound().publish_due_meta();
    const auto& published = uns.publisher.published;
    EXPECT_TRUE(published.empty());  // nothing is due before a connection

    uns.northbound().republish_meta();
    EXPECT_TRUE(published.empty());  // due, not yet sent
    const std::size_t expected[] = {per_call, 2 * per_call, 2 * per_call + 1, 2 * per_call + 1};
    for (const auto count : expected) {
        uns.northbound().publish_due_meta();
        EXPECT_EQ(published.size(), count);
    }
    for (std::size_t i = 0; i < published.size(); ++i) {
        EXPECT_EQ(published[i].topic, plans[i].meta_topic);
    }

    // A reload in the middle of a republish starts it again: every description reaches the
    // broker, whatever the new set.
    uns.publisher.published.clear();
    uns.northbound().republish_meta();
    uns.northbound().publish_due_meta();
    running.consumed.pop_back();
    uns.northbound().exchanges_changed(running, {});
    for (int i = 0; i < 3; ++i) uns.northbound().publish_due_meta();
    ASSERT_EQ(published.size(), per_call + 2 * per_call);
    EXPECT_EQ(published[per_call].topic, plans[0].meta_topic);
    EXPECT_EQ(published.back().topic, plans[2 * per_call - 1].meta_topic);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
