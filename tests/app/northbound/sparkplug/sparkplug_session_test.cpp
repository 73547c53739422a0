// The edge node's session in a hot-standby pair (docs/redundancy.md): the leader opens it with
// a bdSeq other than that of the pair's last session, and a leader that steps down ends it,
// publishing nothing more until its next connection's births.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"
#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Value;
using core::quality::Quality;
using test::decoded;
using test::now_ms;
using test::SparkplugNodeTest;

std::int64_t bd_seq_of(const adapters::mqtt::Message& message) {
    const auto payload = decoded(message);
    EXPECT_EQ(payload.metrics(0).name(), "bdSeq") << message.topic;
    return static_cast<std::int64_t>(payload.metrics(0).long_value());
}

TEST_F(SparkplugNodeTest, ANewLeadersSessionTakesOneMoreThanTheBdSeqItHeard) {
    EXPECT_FALSE(node_.session_bd_seq().has_value());
    node_.begin_session(std::uint8_t{41});
    EXPECT_EQ(bd_seq_of(node_.next_will()), 42);
    EXPECT_EQ(node_.session_bd_seq(), 42);
    node_.on_connected();
    ASSERT_EQ(topics().front(), "spBv1.0/plant1/NBIRTH/gw1");
    EXPECT_EQ(bd_seq_of(publisher_.published.front()), 42);
    // Its own reconnections go on from there.
    EXPECT_EQ(bd_seq_of(node_.next_will()), 43);
}

TEST_F(SparkplugNodeTest, HavingHeardNoBdSeqASessionTakesTheNodesOwnNext) {
    connect();
    node_.end_session();
    node_.begin_session(std::nullopt);
    EXPECT_EQ(bd_seq_of(node_.next_will()), 1);
}

TEST_F(SparkplugNodeTest, ASessionBegunAfterAFailedConnectTakesItsNewBdSeq) {
    node_.next_will();  // a CONNECT that never connected: its bdSeq would go with the next
    node_.end_session();
    node_.begin_session(std::uint8_t{200});
    EXPECT_EQ(bd_seq_of(node_.next_will()), 201);
}

TEST_F(SparkplugNodeTest, AnEndedSessionPublishesNothingUntilTheNextConnectionsBirths) {
    connect();
    first_datagram();
    first_production();
    node_.end_session();
    EXPECT_FALSE(node_.born());
    EXPECT_FALSE(node_.session_bd_seq().has_value());
    publisher_.published.clear();
    const std::vector<app::TagSample> changed{{1, Value{2.5f}}};
    node_.tag_samples({consumed_, Quality::good, now_ms + 100, false, changed});
    node_.exchange_state(consumed_, core::exchange::ConsumeState::stale);
    node_.exchange_state(consumed_, core::exchange::ConsumeState::ok);
    EXPECT_FALSE(node_.replay({consumed_, Quality::good, now_ms, false, changed}, 7));
    advance(std::chrono::seconds(2));
    EXPECT_TRUE(publisher_.published.empty()) << topics().front();

    node_.begin_session(node_.bd_seq());
    node_.next_will();
    node_.on_connected();
    EXPECT_EQ(topics(),
              (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1", "spBv1.0/plant1/DBIRTH/gw1/in",
                                        "spBv1.0/plant1/DBIRTH/gw1/out"}));
    EXPECT_EQ(bd_seq_of(publisher_.published.front()), 1);
    // The births hold what the node learnt while it was not born.
    EXPECT_EQ(decoded(publisher_.published[1]).metrics(1).float_value(), 2.5f);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
