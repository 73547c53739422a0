// The edge node's births against what the broker takes and how often a host asks: a birth over
// the broker's Maximum Packet Size is not published (seq counts only what was), the device or
// the node is then not born; a flood of rebirth requests makes one rebirth in progress and one
// pending; a failed connect attempt leaves bdSeq as it was; a historical DDATA over the limit
// is refused and not waited for; and `check`'s estimate of a birth is never below what is
// published.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_birth_size.hpp"
#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using core::exchange::ConsumeState;
using core::plan::TagType;
using core::plan::Value;
using core::quality::Quality;
using test::decoded;
using test::now_ms;
using test::SparkplugNodeTest;

constexpr std::size_t big_tags = 200;

/// 200 dints with long names and a unit: a DBIRTH of some 12 kB.
core::plan::ExchangePlan big_plan() {
    std::vector<core::plan::TagSpec> tags;
    for (std::size_t i = 0; i < big_tags; ++i) {
        auto tag = test::test_tag("a_rather_long_tag_name_" + std::to_string(i),
                                  static_cast<std::uint16_t>(4 * i), TagType::dint);
        tag.mutable_extras().unit = "kPa";
        tags.push_back(std::move(tag));
    }
    return test::test_plan("big", core::plan::Direction::consume, 4 * big_tags, std::move(tags));
}

std::vector<TagSample> every_tag(std::size_t count, std::int64_t value) {
    std::vector<TagSample> samples;
    for (std::size_t i = 0; i < count; ++i) samples.push_back({i, Value{value}});
    return samples;
}

class SparkplugNodePacketSizeTest : public SparkplugNodeTest {
protected:
    SparkplugNodePacketSizeTest() {
        node_.exchanges_changed({{&consumed_, &big_}, {&produced_}}, {});
    }

    void datagrams(std::int64_t value) {
        node_.tag_samples({big_, Quality::good, now_ms, false, every_tag(big_tags, value)});
        node_.tag_samples({consumed_, Quality::good, now_ms, false, every_tag(3, value)});
    }

    core::plan::ExchangePlan big_ = big_plan();
};

TEST_F(SparkplugNodePacketSizeTest,
       ADbirthOverTheBrokersLimitIsNotPublishedAndItsDeviceStaysUnborn) {
    node_.next_will();
    node_.on_connected(4000);  // the big device's DBIRTH is some 12 kB, the others' far less
    datagrams(1);
    node_.exchange_state(consumed_, ConsumeState::ok);
    node_.exchange_state(big_, ConsumeState::ok);
    EXPECT_EQ(topics(), (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1",
                                                  "spBv1.0/plant1/DBIRTH/gw1/in"}));
    EXPECT_EQ(node_.stats().births_refused, 1u);
    // A value changes everywhere: DDATA only for the device that was born.
    datagrams(2);
    EXPECT_EQ(count_of("spBv1.0/plant1/DDATA/gw1/big"), 0u);
    EXPECT_EQ(count_of("spBv1.0/plant1/DDATA/gw1/in"), 1u);
    // A rebirth tries again, and is refused again; the node's counters say so in NDATA.
    advance(rebirth_hold);
    rebirth_request();
    EXPECT_EQ(count_of("spBv1.0/plant1/DBIRTH/gw1/big"), 0u);
    EXPECT_EQ(node_.stats().births_refused, 2u);
    node_.gateway_metrics({{}, {}, {}, nullptr, nullptr}, std::chrono::seconds(1));
    // seq counts what was published, with no gap for what was not.
    const auto all = seqs();
    std::uint64_t expected = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (publisher_.published[i].topic.find("/NBIRTH/") != std::string::npos) expected = 0;
        EXPECT_EQ(all[i], expected++) << publisher_.published[i].topic;
    }
    const auto ndata = decoded(publisher_.published.back());
    EXPECT_EQ(publisher_.published.back().topic, "spBv1.0/plant1/NDATA/gw1");
    bool counted = false;
    const auto nbirth = decoded(publisher_.published.at(0));
    for (const auto& m : ndata.metrics()) {
        const auto& name = nbirth.metrics(static_cast<int>(m.alias())).name();
        if (name == "Sparkplug/births_refused") counted = m.long_value() == 2;
    }
    EXPECT_TRUE(counted);
}

TEST_F(SparkplugNodePacketSizeTest, AnNbirthOverTheLimitLeavesTheWholeNodeUnbornAndSilent) {
    node_.next_will();
    node_.on_connected(100);  // less than any NBIRTH
    datagrams(1);
    node_.exchange_state(consumed_, ConsumeState::ok);
    first_production();
    datagrams(2);
    node_.gateway_metrics({{}, {}, {}, nullptr, nullptr}, std::chrono::seconds(1));
    EXPECT_TRUE(publisher_.published.empty());
    EXPECT_FALSE(node_.born());
    EXPECT_EQ(node_.stats().births_refused, 1u);
    // A node that is not born takes no command.
    node_.on_message(dcmd(test::command(
        {test::by_name("A", adapters::sparkplug::DataType::int32, Value{std::int64_t{5}})})));
    ASSERT_EQ(writes_.size(), 1u);
    EXPECT_EQ(rejection(0), core::write::WriteError::offline);
}

TEST_F(SparkplugNodePacketSizeTest, MaxPacketBytesLowersTheBrokersLimit) {
    SparkplugNode node({"plant1", "gw1", "", 4000, std::nullopt}, publisher_, *this, wall_clock_,
                       [] {});
    node.exchanges_changed({{&big_}, {}}, {});
    node.next_will();
    node.on_connected();  // the broker says nothing: MQTT's own limit
    node.tag_samples({big_, Quality::good, now_ms, false, every_tag(big_tags, 1)});
    node.exchange_state(big_, ConsumeState::ok);
    EXPECT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1"});
    EXPECT_EQ(node.stats().births_refused, 1u);
}

TEST_F(SparkplugNodePacketSizeTest, AHistoricalDdataOverTheLimitIsRefusedAndNotWaitedFor) {
    // 200 lints born at 0: each value a byte in the DBIRTH, ten bytes at -1 in a DDATA.
    std::vector<core::plan::TagSpec> tags;
    for (std::uint16_t i = 0; i < big_tags; ++i) {
        tags.push_back(test::test_tag("L" + std::to_string(i), 8 * i, TagType::lint));
    }
    const auto wide =
        test::test_plan("wide", core::plan::Direction::consume, 8 * big_tags, std::move(tags));
    SparkplugNode node({"plant1", "gw1", "", 0, std::nullopt}, publisher_, *this, wall_clock_,
                       [] {});
    node.exchanges_changed({{&wide}, {}}, {});
    node.tag_samples({wide, Quality::good, now_ms, false, every_tag(big_tags, 0)});
    node.exchange_state(wide, ConsumeState::ok);
    node.next_will();
    node.on_connected();
    ASSERT_EQ(topics().back(), "spBv1.0/plant1/DBIRTH/gw1/wide");
    // A broker whose limit the births just fit.
    const auto birth_bytes = adapters::mqtt::publish_packet_bytes(publisher_.published.back());
    node.next_will();
    node.on_connected(birth_bytes);
    ASSERT_EQ(topics().back(), "spBv1.0/plant1/DBIRTH/gw1/wide");
    publisher_.published.clear();
    // Refused: counted, and false, so that store and forward counts the entry delivered to the
    // node instead of waiting for an acknowledgement that cannot come.
    EXPECT_FALSE(
        node.replay({wide, Quality::good, now_ms - 1000, false, every_tag(big_tags, -1)}, 41));
    EXPECT_TRUE(publisher_.published.empty());
    EXPECT_EQ(node.stats().data_refused, 1u);
    // One that fits is published with the entry's token, for the journal.
    EXPECT_TRUE(node.replay({wide, Quality::good, now_ms - 900, false, every_tag(10, -1)}, 42));
    ASSERT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/DDATA/gw1/wide"});
    EXPECT_EQ(publisher_.published[0].ack_token, 42u);
    EXPECT_TRUE(decoded(publisher_.published[0]).metrics(0).is_historical());
}

TEST_F(SparkplugNodePacketSizeTest, CheckEstimatesEachBirthAtLeastAsLargeAsItIs) {
    const std::vector<core::plan::ExchangePlan> plans{
        test::sparkplug_plan("in", core::plan::Direction::consume), big_plan(),
        test::sparkplug_plan("out", core::plan::Direction::produce)};
    const auto sizes = sparkplug_birth_sizes({"plant1", "gw1", "", 0, 0}, plans);
    ASSERT_EQ(sizes.devices.size(), 3u);
    // The node's births, with real values, never exceed the estimate.
    node_.next_will();
    node_.on_connected();
    datagrams(-123456);
    node_.exchange_state(consumed_, ConsumeState::ok);
    node_.exchange_state(big_, ConsumeState::ok);
    first_production();
    const auto size_of = [&](const std::string& topic) {
        for (const auto& m : publisher_.published) {
            if (m.topic == topic) return adapters::mqtt::publish_packet_bytes(m);
        }
        ADD_FAILURE() << "nothing on " << topic;
        return std::size_t{0};
    };
    EXPECT_GE(sizes.devices[0], size_of("spBv1.0/plant1/DBIRTH/gw1/in"));
    EXPECT_GE(sizes.devices[1], size_of("spBv1.0/plant1/DBIRTH/gw1/big"));
    EXPECT_GE(sizes.devices[2], size_of("spBv1.0/plant1/DBIRTH/gw1/out"));
    EXPECT_GE(sizes.node, size_of("spBv1.0/plant1/NBIRTH/gw1"));
    // And not wildly above: within 10 bytes a tag.
    EXPECT_LE(sizes.devices[1], size_of("spBv1.0/plant1/DBIRTH/gw1/big") + 10 * big_tags);
}

TEST_F(SparkplugNodeTest, AFloodOfRebirthRequestsMakesOneRebirthInProgressAndOnePending) {
    connect();
    first_datagram();
    first_production();
    advance(rebirth_hold);
    publisher_.published.clear();
    // The first request is served at once; the 999 after it, within its second, make one
    // pending rebirth.
    for (int i = 0; i < 1000; ++i) rebirth_request();
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    for (int tick = 0; tick < 99; ++tick) advance(std::chrono::milliseconds(10));
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 1u);
    advance(std::chrono::milliseconds(10));  // a second after the first
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 2u);
    EXPECT_EQ(count_of("spBv1.0/plant1/DBIRTH/gw1/in"), 2u);
    // Nothing was left pending.
    advance(std::chrono::seconds(5));
    EXPECT_EQ(count_of("spBv1.0/plant1/NBIRTH/gw1"), 2u);
    EXPECT_EQ(node_.stats().rebirth_requests, 1000u);
    EXPECT_EQ(node_.stats().node_births, 3u);  // the connection's, and two rebirths
}

TEST_F(SparkplugNodeTest, AConnectAttemptThatFailedLeavesTheBdSeqAsItWas) {
    // Three outages of several failed attempts each: bdSeq 0, 1, 2, 3, never 0, 11, 22, 33.
    for (std::uint64_t connection = 0; connection < 4; ++connection) {
        for (int attempt = 0; attempt < 11; ++attempt) {
            const auto death = decoded(node_.next_will());
            EXPECT_EQ(death.metrics(0).long_value(), connection) << attempt;
        }
        node_.on_connected();
        EXPECT_EQ(decoded(publisher_.published.back()).metrics(0).long_value(), connection);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
