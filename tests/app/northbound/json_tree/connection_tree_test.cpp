// The JSON tree of a connection after the first (`mqtt` as a list): its options from its own
// section, its topics under its own base_topic both ways (RebasedPublisher), and, unless it
// takes writes, no subscription and no write.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/northbound/json_tree/rebased_publisher.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;

core::config::Config two_connections() {
    core::config::Config config;
    config.gateway.id = "gw";
    config.mqtt.base_topic = "acme";
    config.more_mqtt.push_back({});
    auto& enterprise = config.more_mqtt.back();
    enterprise.name = "enterprise";
    enterprise.base_topic = "corp/plant1";
    enterprise.payload = core::config::PayloadFormat::value;
    enterprise.qos = 0;
    return config;
}

class ConnectionTreeTest : public ::testing::Test, public WriteHandler {
protected:
    void on_write(WriteRequest&& request) override { writes_.push_back(std::move(request)); }
    void start(const core::config::Config& config, std::size_t connection) {
        tree_ = std::make_unique<JsonTree>(json_tree_options(config, connection), rebased_, *this);
        tree_->exchanges_changed({{}, {&produced_}}, {});
    }

    test::RecordingPublisher client_;
    RebasedPublisher rebased_{client_, core::plan::TopicRebase("acme", "corp/plant1")};
    core::plan::ExchangePlan produced_ =
        test::test_plan("out", core::plan::Direction::produce, 4,
                        {test::test_tag("A", 0, TagType::dint, true)}, "t1/out");
    std::unique_ptr<JsonTree> tree_;
    std::vector<WriteRequest> writes_;
};

TEST_F(ConnectionTreeTest, ItsOptionsAreItsOwnSections) {
    const auto config = two_connections();
    const auto first = json_tree_options(config, 0);
    EXPECT_TRUE(first.take_writes);
    EXPECT_TRUE(first.rebase.identity());
    EXPECT_EQ(first.more_connection, "");
    const auto enterprise = json_tree_options(config, 1);
    EXPECT_FALSE(enterprise.take_writes);  // the first connection's alone, by default
    EXPECT_EQ(enterprise.publish.format, core::config::PayloadFormat::value);
    EXPECT_EQ(enterprise.publish.qos, 0);
    EXPECT_EQ(first.publish.qos, 1);
    EXPECT_EQ(enterprise.metrics_topic, "corp/plant1/_gateway/gw/metrics");
    EXPECT_EQ(enterprise.more_connection, "enterprise");
}

TEST_F(ConnectionTreeTest, WithoutWritesItSubscribesToNothingAndTakesNoWrite) {
    start(two_connections(), 1);
    EXPECT_TRUE(client_.subscriptions.empty());
    tree_->on_message(rebased_.inward({"corp/plant1/t1/out/A/set", "5", false, "", "", -1}));
    EXPECT_TRUE(writes_.empty());
}

TEST_F(ConnectionTreeTest, ItsTopicsGoOutUnderItsBaseAndWritesComeBackUnderTheFirst) {
    auto config = two_connections();
    config.more_mqtt[0].writes = true;
    start(config, 1);
    EXPECT_EQ(client_.subscriptions,
              (std::vector<std::string>{"corp/plant1/+/set", "corp/plant1/+/+/set"}));
    tree_->on_message(rebased_.inward({"corp/plant1/t1/out/A/set", "5", false, "", "", -1}));
    tree_->on_message(
        rebased_.inward({"corp/plant1/t1/out/A/set", "6", false, "client/replies", "", -1}));
    ASSERT_EQ(writes_.size(), 2u);
    EXPECT_EQ(writes_[0].target, "acme/t1/out/A/set");  // as the plans know it
    tree_->write_result(writes_[0].reply, std::nullopt);
    EXPECT_EQ(client_.published.back().topic, "corp/plant1/t1/out/A/set/result");
    tree_->write_result(writes_[1].reply, std::nullopt);
    EXPECT_EQ(client_.published.back().topic, "client/replies");  // not under a base: as given
    // `_meta` names each tag's topic as this connection says it.
    tree_->republish_meta();
    tree_->publish_due_meta();
    const auto meta = std::find_if(client_.published.begin(), client_.published.end(),
                                   [](const auto& m) { return m.topic.ends_with("/_meta"); });
    ASSERT_NE(meta, client_.published.end());
    EXPECT_EQ(meta->topic, "corp/plant1/t1/out/_meta");
    EXPECT_NE(meta->payload.find(R"("topic":"corp/plant1/t1/out/A")"), std::string::npos)
        << meta->payload;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
