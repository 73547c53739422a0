// The write router with tags laid out by asset (mqtt.topic_template, a tag's own topic): a
// write on a tag's own `…/set` reaches its exchange, and the filters subscribed hear each
// `set` topic once (an MQTT 5 broker delivers a message once per filter it matches).

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/app/northbound/json_tree/write_router.hpp"
#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Direction;
using core::plan::TagType;

core::plan::ExchangePlan laid_out(std::string name, Direction direction, std::uint32_t id,
                                  const core::plan::TopicTemplate& tmpl) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = direction;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = id;
    spec.length = 16;
    spec.topic = name;
    spec.location.levels = {{"asset", name}};
    spec.tags.push_back(test::test_tag("SPEED", 0, TagType::real, direction == Direction::produce));
    auto lube = test::test_tag("LUBE_P", 4, TagType::real, direction == Direction::produce);
    lube.mutable_extras().location.levels = {{"asset", name + "/lube-pump"}};
    lube.mutable_extras().topic_name = "pressure";
    spec.tags.push_back(std::move(lube));
    const core::plan::Location gateway{{{"area", "hall"}}};
    return core::plan::make_exchange_plan(std::move(spec), "acme", {}, {&tmpl, &gateway});
}

class WriteRouterLayoutTest : public ::testing::Test {
protected:
    WriteRouterLayoutTest() {
        router_.add(produced_);
        router_.add(consumed_);
    }

    std::optional<WriteDecision> route(std::string topic, std::string payload) {
        adapters::mqtt::Incoming message;
        message.topic = std::move(topic);
        message.payload = std::move(payload);
        return router_.route(message);
    }

    core::plan::TopicTemplate tmpl_ = [] {
        std::string problem;
        return *core::plan::TopicTemplate::parse("{base}/{area}/{asset}/{tag}", problem);
    }();
    core::plan::ExchangePlan produced_ = laid_out("t1", Direction::produce, 10, tmpl_);
    core::plan::ExchangePlan consumed_ = laid_out("t2", Direction::consume, 2, tmpl_);
    WriteRouter router_{WriteRouterOptions{"acme", false}};
};

TEST_F(WriteRouterLayoutTest, AWriteOnATagsAssetPathReachesItsExchange) {
    const auto decision = route("acme/hall/t1/lube-pump/pressure/set", "2.5");
    ASSERT_TRUE(decision.has_value());
    const auto* routed = std::get_if<ExchangeWrite>(&decision->outcome);
    ASSERT_NE(routed, nullptr);
    EXPECT_EQ(routed->producer, &produced_);
    ASSERT_EQ(routed->writes.size(), 1u);
    EXPECT_EQ(routed->writes[0].tag_index, 1u);
    EXPECT_EQ(decision->reply.topic, "acme/hall/t1/lube-pump/pressure/set/result");
    // The exchange's own `set` stays under its topic.
    const auto whole = route("acme/t1/set", R"({"SPEED": 1, "LUBE_P": 2})");
    ASSERT_TRUE(whole.has_value());
    EXPECT_NE(std::get_if<ExchangeWrite>(&whole->outcome), nullptr);
}

TEST_F(WriteRouterLayoutTest, TheTagsDefaultTopicIsNoLongerItsWriteTopic) {
    EXPECT_FALSE(route("acme/t1/LUBE_P/set", "2.5").has_value());
    EXPECT_FALSE(route("acme/t1/pressure/set", "2.5").has_value());
}

TEST_F(WriteRouterLayoutTest, AConsumedTagOnItsAssetPathIsReadOnly) {
    const auto decision = route("acme/hall/t2/SPEED/set", "1");
    ASSERT_TRUE(decision.has_value());
    const auto* refused = std::get_if<core::write::WriteRejection>(&decision->outcome);
    ASSERT_NE(refused, nullptr);
    EXPECT_EQ(refused->error, core::write::WriteError::read_only);
}

TEST_F(WriteRouterLayoutTest, AResponseTopicThatIsATagsTopicIsRefused) {
    adapters::mqtt::Incoming message;
    message.topic = "acme/hall/t1/SPEED/set";
    message.payload = "1";
    message.response_topic = "acme/hall/t1/lube-pump/pressure";
    const auto decision = router_.route(message);
    ASSERT_TRUE(decision.has_value());
    const auto* refused = std::get_if<core::write::WriteRejection>(&decision->outcome);
    ASSERT_NE(refused, nullptr);
    EXPECT_EQ(refused->error, core::write::WriteError::bad_response_topic);
    EXPECT_EQ(decision->response_topic_problem, "is a tag's topic");
    EXPECT_EQ(decision->reply.topic, "acme/hall/t1/SPEED/set/result");
}

TEST_F(WriteRouterLayoutTest, EachSetTopicIsSubscribedExactlyAndNoFilterOverlapsAnother) {
    EXPECT_EQ(
        router_.subscriptions(),
        (std::vector<std::string>{"acme/hall/t1/SPEED/set", "acme/hall/t1/lube-pump/pressure/set",
                                  "acme/t1/set", "acme/t2/set"}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
