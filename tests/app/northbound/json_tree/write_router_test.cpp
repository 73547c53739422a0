// The write router without a socket: which topics are ours, where results go, and what is
// refused before anything is staged (docs/mqtt-api.md "Writes").

#include "eip2mqtt/app/northbound/json_tree/write_router.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::write::WriteError;
using core::write::WriteRejection;

core::plan::ExchangePlan plan(std::string name, core::plan::Direction direction,
                              std::uint32_t exchange_id) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = direction;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = exchange_id;
    spec.length = 16;
    spec.topic = "t1/" + name;
    spec.tags.push_back(test::test_tag("SPEED", 0, TagType::real, true));
    spec.tags.push_back(test::test_tag("COUNT", 4, TagType::lint, true));
    spec.tags.push_back(test::test_tag("FIXED", 12, TagType::int_, false));
    spec.tags.push_back(
        test::test_tag("COUNT_LO", 4, TagType::dint, true));  // the low half of COUNT
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

class WriteRouterTest : public ::testing::Test {
protected:
    WriteRouterTest() {
        router_.add(produced_);
        router_.add(consumed_);
    }

    WriteDecision route(std::string topic, std::string payload, std::string response_topic = {},
                        bool retained = false) {
        adapters::mqtt::Incoming message;
        message.topic = std::move(topic);
        message.payload = std::move(payload);
        message.response_topic = std::move(response_topic);
        message.correlation_data = "id-1";
        message.retained = retained;
        auto decision = router_.route(message);
        EXPECT_TRUE(decision.has_value()) << message.topic;
        return decision ? std::move(*decision) : WriteDecision{};
    }
    static WriteRejection refused(const WriteDecision& decision) {
        const auto* rejection = std::get_if<WriteRejection>(&decision.outcome);
        EXPECT_NE(rejection, nullptr);
        return rejection ? *rejection : WriteRejection{WriteError::empty, "accepted"};
    }
    static ExchangeWrite accepted(const WriteDecision& decision) {
        const auto* routed = std::get_if<ExchangeWrite>(&decision.outcome);
        EXPECT_NE(routed, nullptr)
            << (routed ? "" : std::get<WriteRejection>(decision.outcome).message);
        return routed ? *routed : ExchangeWrite{};
    }

    core::plan::ExchangePlan produced_ = plan("sp", core::plan::Direction::produce, 10);
    core::plan::ExchangePlan consumed_ = plan("in", core::plan::Direction::consume, 2);
    WriteRouter router_{WriteRouterOptions{"acme", false}};
};

TEST_F(WriteRouterTest, AnEmptyMessageClearsARetainedWriteAndIsNoWriteAtAll) {
    // What the broker passes on when a client clears a retained `set` message: no write, no
    // rejection, no result.
    for (const bool retained : {false, true}) {
        for (const auto* topic : {"acme/t1/sp/SPEED/set", "acme/t1/sp/set", "acme/t1/in/A/set"}) {
            adapters::mqtt::Incoming message;
            message.topic = topic;
            message.retained = retained;
            EXPECT_FALSE(router_.route(message).has_value()) << topic;
        }
    }
}

TEST_F(WriteRouterTest, ATagWriteGoesToItsProducerAndAnswersOnItsResultTopic) {
    const auto decision = route("acme/t1/sp/SPEED/set", "12.5");
    const auto routed = accepted(decision);
    EXPECT_EQ(routed.producer, &produced_);
    ASSERT_EQ(routed.writes.size(), 1u);
    EXPECT_EQ(routed.writes[0].tag_index, 0u);
    EXPECT_EQ(routed.writes[0].value, core::plan::Value{12.5F});
    EXPECT_EQ(decision.reply.topic, "acme/t1/sp/SPEED/set/result");
    EXPECT_EQ(decision.reply.correlation_data, "id-1");
}

TEST_F(WriteRouterTest, AnExchangeWriteCarriesEveryTagOrNone) {
    const auto routed = accepted(route("acme/t1/sp/set", R"({"SPEED":1,"COUNT":-3})"));
    ASSERT_EQ(routed.writes.size(), 2u);
    EXPECT_EQ(routed.writes[1].tag_index, 1u);
    EXPECT_EQ(routed.writes[1].value, core::plan::Value{std::int64_t{-3}});
    const auto rejection = refused(route("acme/t1/sp/set", R"({"SPEED":1,"COUNT":0.5})"));
    EXPECT_EQ(rejection.error, WriteError::not_integer);
    EXPECT_EQ(rejection.message, "COUNT: expected an integer");
}

TEST_F(WriteRouterTest, OverlappingTagsAreWrittenOneAtATimeNeverTogether) {
    EXPECT_EQ(accepted(route("acme/t1/sp/COUNT_LO/set", "5")).writes.size(), 1u);
    EXPECT_EQ(accepted(route("acme/t1/sp/set", R"({"SPEED":1,"COUNT_LO":5})")).writes.size(), 2u);
    const auto rejection =
        refused(route("acme/t1/sp/set", R"({"SPEED":1,"COUNT_LO":5,"COUNT":3})"));
    EXPECT_EQ(rejection.error, WriteError::overlapping_tags);
    EXPECT_EQ(rejection.message,
              "tags COUNT_LO and COUNT share bytes; write them in separate messages");
}

TEST_F(WriteRouterTest, TopicsThatAreNotOursAreIgnored) {
    adapters::mqtt::Incoming message;
    for (const auto* topic : {"acme/t1/sp/SPEED", "acme/t2/sp/set", "other/set", "set",
                              "acme/t1/sp/SPEED/set/result"}) {
        message.topic = topic;
        EXPECT_FALSE(router_.route(message).has_value()) << topic;
    }
}

TEST_F(WriteRouterTest, UnknownReadOnlyConsumedAndRetainedWritesAreRefused) {
    EXPECT_EQ(refused(route("acme/t1/sp/NOPE/set", "1")).message,
              "unknown tag NOPE in exchange sp");
    EXPECT_EQ(refused(route("acme/t1/sp/FIXED/set", "1")).error, WriteError::read_only);
    EXPECT_EQ(refused(route("acme/t1/in/SPEED/set", "1")).error, WriteError::read_only);
    EXPECT_EQ(refused(route("acme/t1/sp/SPEED/set", "1", {}, true)).error, WriteError::retained);
}

TEST_F(WriteRouterTest, ARetainedWriteIsToldHowToClearIt) {
    // Left on the broker, it is refused again at every reconnect until someone clears it.
    const auto message = refused(route("acme/t1/sp/SPEED/set", "1", {}, true)).message;
    EXPECT_NE(message.find("mosquitto_pub -r -n -t 'acme/t1/sp/SPEED/set'"), std::string::npos)
        << message;
}

TEST_F(WriteRouterTest, AnUnknownTagWhoseResultTopicNoBrokerAcceptsIsRefusedUnanswered) {
    // `acme/t1/sp/{name}/set` fits in 65,535 bytes; with `/result` it would not. The fuzzer also
    // found a name that is not UTF-8 (which no conforming broker delivers).
    const std::string long_name(65535 - std::string("acme/t1/sp//set").size(), 'n');
    for (const auto& name : {long_name, std::string("L\xEB")}) {
        const auto decision = route("acme/t1/sp/" + name + "/set", "1");
        EXPECT_EQ(refused(decision).error, WriteError::unknown_tag);
        EXPECT_EQ(decision.reply.topic, "");
        // A good response topic is still answered.
        EXPECT_EQ(route("acme/t1/sp/" + name + "/set", "1", "clients/r").reply.topic, "clients/r");
    }
}

TEST_F(WriteRouterTest, AValidResponseTopicGetsTheResult) {
    const auto decision = route("acme/t1/sp/SPEED/set", "1", "clients/hmi-3/replies");
    accepted(decision);
    EXPECT_EQ(decision.reply.topic, "clients/hmi-3/replies");
    EXPECT_EQ(decision.reply.correlation_data, "id-1");
}

TEST_F(WriteRouterTest, AResponseTopicNoBrokerAcceptsIsRefusedAndAnsweredOnTheResultTopic) {
    const std::vector<std::string> topics{
        "rt/#",
        "a/+/b",
        "#",
        std::string(65536, 'r'),
        "a\nb",
        std::string("a\0b", 3),
        "\xC3(",
        "\xEF\xBF\xBF",
        "clients/\xE2\x80\xAEylper"};  // the last: an RLO (U+202E)
    for (const auto& topic : topics) {
        const auto decision = route("acme/t1/sp/SPEED/set", "1", topic);
        const auto rejection = refused(decision);
        EXPECT_EQ(rejection.error, WriteError::bad_response_topic) << topic.substr(0, 10);
        EXPECT_EQ(rejection.message, "bad response topic");
        EXPECT_EQ(decision.reply.topic, "acme/t1/sp/SPEED/set/result");
        EXPECT_FALSE(decision.response_topic_problem.empty());
    }
    // 65,535 bytes is the most a topic may have, and is accepted.
    EXPECT_EQ(route("acme/t1/sp/SPEED/set", "1", std::string(65535, 'r')).reply.topic.size(),
              65535u);
}

TEST_F(WriteRouterTest, AResponseTopicAmongTheGatewaysOwnTopicsIsRefused) {
    for (const auto* topic :
         {"acme/_gateway/gw/state", "acme/t1/in/PRESSURE", "acme/t1/sp/SPEED", "acme/t1/sp/_status",
          "acme", "acme/t1/sp/SPEED/set", "acme/t1/sp/set"}) {
        const auto decision = route("acme/t1/sp/SPEED/set", "1", topic);
        EXPECT_EQ(refused(decision).error, WriteError::bad_response_topic) << topic;
        EXPECT_EQ(decision.reply.topic, "acme/t1/sp/SPEED/set/result") << topic;
    }
    // Below a `set` level the gateway publishes only results; other topics that merely begin
    // with the same characters are not under the base topic.
    for (const auto* topic : {"acme/t1/sp/SPEED/set/result", "acme/t1/sp/set/mine", "acmex/r"}) {
        EXPECT_EQ(route("acme/t1/sp/SPEED/set", "1", topic).reply.topic, topic);
    }
}

TEST_F(WriteRouterTest, ResponseTopicsUnderTheBaseCanBeAllowed) {
    router_.set_options({"acme", true});
    EXPECT_EQ(route("acme/t1/sp/SPEED/set", "1", "acme/replies").reply.topic, "acme/replies");
    // Never what a broker refuses.
    EXPECT_EQ(refused(route("acme/t1/sp/SPEED/set", "1", "acme/#")).error,
              WriteError::bad_response_topic);
}

TEST_F(WriteRouterTest, OneFilterPerDepthOfSetTopic) {
    auto filters = router_.subscriptions();
    std::sort(filters.begin(), filters.end());
    EXPECT_EQ(filters, (std::vector<std::string>{"acme/+/+/+/set", "acme/+/+/set"}));
    router_.clear();
    EXPECT_TRUE(router_.subscriptions().empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
