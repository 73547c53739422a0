// What a host sends the edge node, against the node's state: a DCMD while the node is not born
// is refused (`offline`) and writes nothing, as the specification expects of an offline edge
// node; the primary host's STATE going offline and online again keeps each NDEATH before the
// next NBIRTH, whatever the data's QoS, and a host that flaps costs one birth a second.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

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

class SparkplugStateFlapTest : public SparkplugPrimaryHostTest,
                               public ::testing::WithParamInterface<int> {
protected:
    SparkplugStateFlapTest() : SparkplugPrimaryHostTest(GetParam()) {}
};

TEST_P(SparkplugStateFlapTest, BirthsWaitForTheBrokersAcknowledgementOfTheNdeath) {
    connect();
    first_production();
    state(true, 100);
    ASSERT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    state(false, 200);
    const auto& death = publisher_.published.back();
    ASSERT_EQ(death.topic, "spBv1.0/plant1/NDEATH/gw1");
    EXPECT_EQ(death.qos, 1);
    const auto token = death.ack_token;
    EXPECT_NE(token, 0u);
    state(true, 300);
    advance(rebirth_hold * 3);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);  // the NDEATH is not acknowledged
    node_.on_acknowledged(token + 1);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);  // another publication's
    node_.on_acknowledged(token);
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 2u);
    EXPECT_EQ(topics().back(), "spBv1.0/plant1/DBIRTH/gw1/out");
}

TEST_P(SparkplugStateFlapTest, AJournalEntrysAcknowledgementIsNotTheNodesOwn) {
    // The node's connection carries its NDEATH's token and the journal's entry ids (historical
    // DDATA): the gateway hands each acknowledgement to the node first, the rest to the journal.
    connect();
    first_production();
    state(true, 100);
    state(false, 200);
    const auto token = publisher_.published.back().ack_token;
    state(true, 300);
    advance(rebirth_hold * 3);
    // Entry ids count from 1, as the node's own tokens do: none of them may pass for its NDEATH.
    for (const std::uint64_t id :
         {std::uint64_t{1}, std::uint64_t{2}, token & ~sparkplug_own_token}) {
        EXPECT_FALSE(node_.on_acknowledged(id)) << id;
    }
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    EXPECT_TRUE(node_.on_acknowledged(token));
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 2u);
    EXPECT_EQ(topics().back(), "spBv1.0/plant1/DBIRTH/gw1/out");
}

TEST_P(SparkplugStateFlapTest, AFlappingHostCostsABirthASecondAndEveryDeathComesBeforeItsBirth) {
    connect();
    first_production();
    std::int64_t timestamp = 0;
    // The broker answers each NDEATH by the next tick.
    const auto tick = [&] {
        advance(std::chrono::milliseconds(1));
        const auto& last = publisher_.published.back();
        if (last.topic == "spBv1.0/plant1/NDEATH/gw1") node_.on_acknowledged(last.ack_token);
    };
    for (int flap = 0; flap < 1500; ++flap) {
        state(true, ++timestamp);
        tick();
        state(false, ++timestamp);
        tick();
    }
    state(true, ++timestamp);
    advance(rebirth_hold);
    // NBIRTH and NDEATH alternate, and never two births without a death between them.
    std::vector<std::string> node_messages;
    for (const auto& topic : topics()) {
        if (topic.find("/DBIRTH/") == std::string::npos) node_messages.push_back(topic);
    }
    ASSERT_FALSE(node_messages.empty());
    for (std::size_t i = 0; i < node_messages.size(); ++i) {
        EXPECT_EQ(node_messages[i],
                  i % 2 == 0 ? "spBv1.0/plant1/NBIRTH/gw1" : "spBv1.0/plant1/NDEATH/gw1")
            << i;
    }
    EXPECT_EQ(node_messages.size() % 2, 1u);  // born at the end
    // 1,501 times online in 3 s: a birth a second at most, the host's last return included.
    EXPECT_GE(count_of("spBv1.0/plant1/NBIRTH/gw1"), 3u);
    EXPECT_LE(count_of("spBv1.0/plant1/NBIRTH/gw1"), 5u);
}

INSTANTIATE_TEST_SUITE_P(DataQos, SparkplugStateFlapTest, ::testing::Values(0, 1));

}  // namespace
}  // namespace eip2mqtt::app::northbound::sparkplug
