// What a host sends the edge node, against the node's state: a DCMD while the node is not born
// is refused (`offline`) and writes nothing, as the specification expects of an offline edge
// node; the primary host's STATE going offline makes a born node leave its broker (its NDEATH,
// DISCONNECT, the next broker), where births wait for the host's STATE online.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::DataType;
using core::plan::Value;
using core::write::WriteError;
using test::by_name;
using test::command;
using test::SparkplugNodeTest;
using test::SparkplugPrimaryHostTest;

std::string a_write() { return command({by_name("A", DataType::int32, Value{std::int64_t{5}})}); }

TEST_F(SparkplugNodeTest, ADcmdBeforeTheNodeIsBornIsRefusedOffline) {
    first_production();
    node_.on_message(dcmd(a_write()));  // not connected yet
    connect();
    node_.on_message(dcmd(a_write()));  // born: taken
    ASSERT_EQ(writes_.size(), 2u);
    EXPECT_EQ(rejection(0), WriteError::offline);
    EXPECT_TRUE(std::holds_alternative<ExchangeWrite>(writes_[1].outcome));
}

TEST_F(SparkplugPrimaryHostTest, ADcmdWithoutTheHostsStateOrAfterTheNdeathIsRefusedOffline) {
    connect();
    first_production();
    node_.on_message(dcmd(a_write()));  // connected, but no STATE yet: not born
    state(true, 100);
    node_.on_message(dcmd(a_write()));  // born
    state(false, 200);
    node_.on_message(dcmd(a_write()));  // after its NDEATH
    ASSERT_EQ(writes_.size(), 3u);
    EXPECT_EQ(rejection(0), WriteError::offline);
    EXPECT_TRUE(std::holds_alternative<ExchangeWrite>(writes_[1].outcome));
    EXPECT_EQ(rejection(2), WriteError::offline);
    EXPECT_EQ(std::get<core::write::WriteRejection>(writes_[2].outcome).message,
              "the Sparkplug edge node is offline (not born)");
}

TEST_F(SparkplugPrimaryHostTest, TheHostOfflineMakesTheBornNodeLeaveItsBrokerAndWaitOnTheNext) {
    connect();
    first_production();
    state(true, 100);
    ASSERT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    const auto said = publisher_.published.size();
    state(false, 200);
    // Its NDEATH is the connection's will, said by the client as it leaves (Client::leave_broker).
    EXPECT_EQ(brokers_left_, 1);
    EXPECT_FALSE(node_.born());
    first_production();
    advance(rebirth_hold * 3);
    EXPECT_EQ(publisher_.published.size(), said);  // nothing more on this broker
    // The next broker: a new will, and births only once the host says it is online there.
    const auto bd_seq = node_.bd_seq();
    connect();
    EXPECT_EQ(node_.bd_seq(), bd_seq + 1);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    state(true, 300);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 2u);
    EXPECT_EQ(topics().back(), "spBv1.0/plant1/DBIRTH/gw1/out");
}

TEST_F(SparkplugPrimaryHostTest, AnOfflineStateOlderThanTheLastOnlineOneKeepsTheNodeOnItsBroker) {
    connect();
    state(true, 200);
    state(false, 150);
    EXPECT_EQ(brokers_left_, 0);
    EXPECT_TRUE(node_.born());
}

TEST_F(SparkplugPrimaryHostTest, ANodeNotBornYetWaitsForTheHostOnItsBroker) {
    connect();
    state(false, 100);
    EXPECT_EQ(brokers_left_, 0);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 0u);
    state(true, 200);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
