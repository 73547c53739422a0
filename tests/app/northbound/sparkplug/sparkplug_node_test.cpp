// The Sparkplug B edge node over a recording publisher: births, bdSeq and seq, DDATA
// by alias, DDEATH and rebirth of a device, NCMD rebirth, DCMD writes accepted and refused, and
// the primary host's STATE. Payloads are read back with the protobuf classes of our .proto; the
// integration test reads them with Eclipse Tahu's decoder.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::DataType;
using core::exchange::ConsumeState;
using core::plan::Value;
using core::quality::Quality;
using core::write::WriteError;
using test::by_name;
using test::command;
using test::decoded;
using test::now_ms;
using test::SparkplugNodeTest;
using test::SparkplugPrimaryHostTest;
using Proto = test::SparkplugProto;

core::plan::ExchangePlan plan(std::string name, core::plan::Direction direction) {
    return test::sparkplug_plan(std::move(name), direction);
}

TEST_F(SparkplugNodeTest, SubscribesToItsCommandsBeforeAnyBirth) {
    EXPECT_EQ(publisher_.subscriptions,
              (std::vector<std::string>{"spBv1.0/plant1/NCMD/gw1", "spBv1.0/plant1/DCMD/gw1/+"}));
    EXPECT_TRUE(publisher_.published.empty());
}

TEST_F(SparkplugNodeTest, EachConnectionHasANewBdSeqThatItsNbirthCarries) {
    for (int connection = 0; connection < 258; ++connection) {
        const auto will = node_.next_will();
        EXPECT_EQ(will.topic, "spBv1.0/plant1/NDEATH/gw1");
        EXPECT_EQ(will.qos, 1);
        EXPECT_FALSE(will.retain);
        const auto death = decoded(will);
        EXPECT_FALSE(death.has_seq());
        ASSERT_EQ(death.metrics_size(), 1);
        EXPECT_EQ(death.metrics(0).name(), "bdSeq");
        EXPECT_EQ(death.metrics(0).long_value(), static_cast<std::uint64_t>(connection % 256));
        publisher_.published.clear();
        node_.on_connected();
        ASSERT_EQ(topics().front(), "spBv1.0/plant1/NBIRTH/gw1");
        const auto birth = decoded(publisher_.published.front());
        EXPECT_EQ(birth.seq(), 0u);
        EXPECT_EQ(birth.metrics(0).name(), "bdSeq");
        EXPECT_EQ(birth.metrics(0).long_value(), death.metrics(0).long_value());
    }
}

TEST_F(SparkplugNodeTest, NbirthListsRebirthAndTheNodeCounters) {
    node_.next_will();
    node_.on_connected();
    const auto birth = decoded(publisher_.published.at(0));
    std::vector<std::string> names;
    for (const auto& m : birth.metrics()) names.push_back(m.name());
    EXPECT_EQ(names.at(1), "Node Control/Rebirth");
    EXPECT_FALSE(birth.metrics(1).boolean_value());
    EXPECT_NE(std::find(names.begin(), names.end(), "Gateway/accepted"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "Exchanges/in/state"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "Exchanges/out/sent"), names.end());
    // Each metric's alias is its place, but Rebirth's: Sparkplug B 3.0 forbids one on it.
    EXPECT_FALSE(birth.metrics(1).has_alias());
    for (int i = 0; i < birth.metrics_size(); ++i) {
        if (i == 1) continue;
        EXPECT_EQ(birth.metrics(i).alias(), static_cast<std::uint64_t>(i)) << names[i];
    }
}

TEST_F(SparkplugNodeTest, DevicesAreBornWithEveryTagOnceTheirValuesAreKnown) {
    node_.next_will();
    node_.on_connected();
    EXPECT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1"});
    first_datagram();
    first_production();
    EXPECT_EQ(topics(),
              (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1", "spBv1.0/plant1/DBIRTH/gw1/in",
                                        "spBv1.0/plant1/DBIRTH/gw1/out"}));
    EXPECT_EQ(seqs(), (std::vector<std::uint64_t>{0, 1, 2}));
    const auto in = decoded(publisher_.published[1]);
    ASSERT_EQ(in.metrics_size(), 3);
    EXPECT_EQ(in.metrics(0).name(), "A");
    EXPECT_EQ(in.metrics(0).datatype(), static_cast<std::uint32_t>(DataType::int32));
    EXPECT_EQ(in.metrics(0).int_value(), 7u);
    EXPECT_EQ(in.metrics(0).timestamp(), static_cast<std::uint64_t>(now_ms - 5));
    EXPECT_EQ(in.metrics(1).datatype(), static_cast<std::uint32_t>(DataType::float32));
    EXPECT_EQ(in.metrics(1).float_value(), 1.5f);
    EXPECT_NE(in.metrics(0).alias(), in.metrics(1).alias());
    ASSERT_EQ(in.metrics(0).properties().keys_size(), 1);  // consumed: the unit only
    EXPECT_EQ(in.metrics(0).properties().keys(0), "engUnit");
    EXPECT_EQ(in.metrics(0).properties().values(0).string_value(), "rpm");
    const auto out = decoded(publisher_.published[2]);
    const auto& props = out.metrics(0).properties();
    ASSERT_EQ(props.keys_size(), 3);
    EXPECT_EQ(props.keys(1), "writable");
    EXPECT_TRUE(props.values(1).boolean_value());
    EXPECT_EQ(props.keys(2), "max");
    EXPECT_EQ(props.values(2).double_value(), 4000.0);
    // Aliases are unique across the node, devices included.
    EXPECT_NE(in.metrics(0).alias(), out.metrics(0).alias());
}

TEST_F(SparkplugNodeTest, DdataCarriesTheChangedTagsByAliasWithTheirTimestamp) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    const auto birth = decoded(publisher_.published.back());
    publisher_.published.clear();
    const std::vector<TagSample> changed{{1, Value{2.5f}}};
    node_.tag_samples({consumed_, Quality::good, now_ms + 100, false, changed});
    ASSERT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/DDATA/gw1/in"});
    const auto data = decoded(publisher_.published[0]);
    EXPECT_EQ(data.seq(), 2u);
    ASSERT_EQ(data.metrics_size(), 1);
    EXPECT_FALSE(data.metrics(0).has_name());
    EXPECT_EQ(data.metrics(0).alias(), birth.metrics(1).alias());
    EXPECT_EQ(data.metrics(0).timestamp(), static_cast<std::uint64_t>(now_ms + 100));
    EXPECT_EQ(data.metrics(0).float_value(), 2.5f);
    // The JSON tree's republication of every tag is no news to a Sparkplug host.
    const std::vector<TagSample> all{{0, Value{std::int64_t{7}}}, {1, Value{2.5f}}};
    node_.tag_samples({consumed_, Quality::good, now_ms + 200, true, all});
    EXPECT_EQ(publisher_.published.size(), 1u);
}

TEST_F(SparkplugNodeTest, DdataCarriesOnlyWhatChangedSinceTheBirthOrTheLastDdata) {
    node_.next_will();
    node_.on_connected();
    first_datagram();  // born with A 7, B 1.5, C 0
    publisher_.published.clear();
    // The JSON tree's republication after `refresh_s` (B unchanged), with A changed.
    const std::vector<TagSample> refreshed{{0, Value{std::int64_t{8}}}, {1, Value{1.5f}}};
    node_.tag_samples({consumed_, Quality::good, now_ms + 100, false, refreshed});
    ASSERT_EQ(publisher_.published.size(), 1u);
    const auto data = decoded(publisher_.published[0]);
    ASSERT_EQ(data.metrics_size(), 1);
    EXPECT_EQ(data.metrics(0).int_value(), 8u);
    // Nothing changed at all: no DDATA.
    node_.tag_samples({consumed_, Quality::good, now_ms + 200, false, refreshed});
    EXPECT_EQ(publisher_.published.size(), 1u);
}

TEST_F(SparkplugNodeTest, ReplayedHistoryIsDdataWithEveryMetricHistoricalForABornDeviceOnly) {
    const std::vector<TagSample> journaled{{1, Value{3.5f}}, {2, Value{std::int64_t{4}}}};
    // Not born yet: the host could not resolve the aliases.
    node_.replay({consumed_, Quality::good, now_ms - 60000, false, journaled}, 0);
    EXPECT_TRUE(publisher_.published.empty());

    node_.next_will();
    node_.on_connected();
    first_datagram();
    const auto birth = decoded(publisher_.published.back());
    publisher_.published.clear();
    node_.replay({consumed_, Quality::good, now_ms - 60000, false, journaled}, 0);
    ASSERT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/DDATA/gw1/in"});
    const auto data = decoded(publisher_.published[0]);
    ASSERT_EQ(data.metrics_size(), 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_TRUE(data.metrics(i).is_historical());
        EXPECT_FALSE(data.metrics(i).has_name());
        EXPECT_EQ(data.metrics(i).alias(), birth.metrics(i + 1).alias());
        EXPECT_EQ(data.metrics(i).timestamp(), static_cast<std::uint64_t>(now_ms - 60000));
    }
    EXPECT_EQ(data.metrics(0).float_value(), 3.5f);
    // A stale sample is no data in this convention (a DDEATH said it when it happened).
    node_.replay({consumed_, Quality::stale, now_ms - 50000, false, journaled}, 0);
    EXPECT_EQ(publisher_.published.size(), 1u);
    // Live DDATA stays live.
    node_.tag_samples({consumed_, Quality::good, now_ms + 100, false, journaled});
    ASSERT_EQ(publisher_.published.size(), 2u);
    EXPECT_FALSE(decoded(publisher_.published[1]).metrics(0).is_historical());
}

TEST_F(SparkplugNodeTest, AReloadBringsEveryBirthAgainAndAKeptExchangeKeepsItsValues) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    const auto added = plan("added", core::plan::Direction::consume);
    publisher_.published.clear();
    node_.exchanges_changed({{&consumed_, &added}, {}}, {});
    // The node's metrics changed (a device more, one less): NBIRTH, then the devices that are up.
    EXPECT_EQ(topics(), (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1",
                                                  "spBv1.0/plant1/DBIRTH/gw1/in"}));
    EXPECT_EQ(decoded(publisher_.published[1]).metrics(0).int_value(), 7u);
    const auto birth = decoded(publisher_.published[0]);
    bool named = false;
    for (const auto& m : birth.metrics()) named = named || m.name() == "Exchanges/added/state";
    EXPECT_TRUE(named);
    for (const auto& m : birth.metrics()) EXPECT_NE(m.name(), "Exchanges/out/state");
}

TEST_F(SparkplugNodeTest, SeqRunsFrom0To255ThenStartsAgain) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    for (int i = 0; i < 300; ++i) {
        const std::vector<TagSample> changed{{0, Value{std::int64_t{i}}}};
        node_.tag_samples({consumed_, Quality::good, now_ms, false, changed});
    }
    const auto all = seqs();
    for (std::size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], i % 256) << i;
}

TEST_F(SparkplugNodeTest, AStaleExchangeDiesAndIsBornAgainWithItsFirstGoodDatagram) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    publisher_.published.clear();
    const std::vector<TagSample> stale{{0, Value{std::int64_t{7}}}, {1, Value{1.5f}}};
    node_.tag_samples({consumed_, Quality::stale, now_ms + 1000, false, stale});
    node_.exchange_state(consumed_, ConsumeState::stale);
    EXPECT_EQ(topics(), std::vector<std::string>{"spBv1.0/plant1/DDEATH/gw1/in"});
    const std::vector<TagSample> back{{0, Value{std::int64_t{8}}}, {1, Value{1.5f}}};
    node_.tag_samples({consumed_, Quality::good, now_ms + 2000, false, back});
    node_.exchange_state(consumed_, ConsumeState::ok);
    EXPECT_EQ(topics(), (std::vector<std::string>{"spBv1.0/plant1/DDEATH/gw1/in",
                                                  "spBv1.0/plant1/DBIRTH/gw1/in"}));
    const auto reborn = decoded(publisher_.published[1]);
    EXPECT_EQ(reborn.metrics(0).int_value(), 8u);
    EXPECT_EQ(reborn.metrics(0).timestamp(), static_cast<std::uint64_t>(now_ms + 2000));
}

TEST_F(SparkplugNodeTest, NcmdRebirthBringsEveryBirthAgainFromSeq0) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    first_production();
    publisher_.published.clear();
    // At once, however soon after the connection's births.
    adapters::mqtt::Incoming ncmd;
    ncmd.topic = "spBv1.0/plant1/NCMD/gw1";
    ncmd.payload = command({by_name("Node Control/Rebirth", DataType::boolean, Value{true})});
    node_.on_message(ncmd);
    EXPECT_EQ(topics(),
              (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1", "spBv1.0/plant1/DBIRTH/gw1/in",
                                        "spBv1.0/plant1/DBIRTH/gw1/out"}));
    EXPECT_EQ(seqs(), (std::vector<std::uint64_t>{0, 1, 2}));
    // Hostile bytes on NCMD: ignored, nothing published.
    ncmd.payload = "\xff\xff\xff";
    node_.on_message(ncmd);
    EXPECT_EQ(publisher_.published.size(), 3u);
}

TEST_F(SparkplugNodeTest, ADcmdIsOneWriteOfEveryMetricByNameOrAlias) {
    node_.next_will();
    node_.on_connected();
    first_production();
    const auto birth = decoded(publisher_.published.back());
    adapters::sparkplug::Metric by_alias{
        "", birth.metrics(1).alias(), now_ms, DataType::float32, Value{2.5f}, false, {}};
    node_.on_message(
        dcmd(command({by_name("A", DataType::int32, Value{std::int64_t{1200}}), by_alias})));
    ASSERT_EQ(writes_.size(), 1u);
    EXPECT_EQ(writes_[0].reply.origin, &node_);
    const auto& write = std::get<ExchangeWrite>(writes_[0].outcome);
    EXPECT_EQ(write.producer, &produced_);
    ASSERT_EQ(write.writes.size(), 2u);
    EXPECT_EQ(write.writes[0].tag_index, 0u);
    EXPECT_TRUE(core::plan::same_value(write.writes[0].value, Value{std::int64_t{1200}}));
    EXPECT_EQ(write.writes[1].tag_index, 1u);
    EXPECT_TRUE(core::plan::same_value(write.writes[1].value, Value{2.5f}));
}

TEST_F(SparkplugNodeTest, ARefusedDcmdSaysWhyAndWritesNothing) {
    connect();
    const auto a = [](Value v) { return by_name("A", DataType::int32, v); };
    node_.on_message(dcmd(command({a(Value{std::int64_t{5000}})})));  // over max 4000
    node_.on_message(
        dcmd(command({by_name("C", DataType::int32, Value{std::int64_t{1}})})));  // read-only
    node_.on_message(dcmd(command({by_name("Z", DataType::int32, Value{std::int64_t{1}})})));
    node_.on_message(dcmd(command({by_name("A", DataType::boolean, Value{true})})));  // for a dint
    node_.on_message(dcmd("\x0a\xff\xff"));                                   // not protobuf
    node_.on_message(dcmd(command({})));                                      // no metric
    node_.on_message(dcmd(command({a(Value{std::int64_t{1}})}), "in"));       // consumed
    node_.on_message(dcmd(command({a(Value{std::int64_t{1}})}), "nowhere"));  // no such device
    auto retained = dcmd(command({a(Value{std::int64_t{1}})}));
    retained.retained = true;
    node_.on_message(retained);
    // One valid metric and one bad: nothing of it is written.
    node_.on_message(dcmd(command({a(Value{std::int64_t{1}}), a(Value{std::int64_t{9000}})})));
    const std::vector<WriteError> expected{WriteError::above_max,   WriteError::read_only,
                                           WriteError::unknown_tag, WriteError::wrong_type,
                                           WriteError::malformed,   WriteError::empty,
                                           WriteError::read_only,   WriteError::unknown_tag,
                                           WriteError::retained,    WriteError::above_max};
    ASSERT_EQ(writes_.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        ASSERT_TRUE(std::holds_alternative<core::write::WriteRejection>(writes_[i].outcome)) << i;
        EXPECT_EQ(rejection(i), expected[i]) << i;
        EXPECT_EQ(writes_[i].reply.origin, &node_);
    }
}

TEST_F(SparkplugNodeTest, AnEmptyDcmdClearsARetainedCommandAndIsNoWriteAtAll) {
    node_.next_will();
    node_.on_connected();
    first_production();
    for (const bool retained : {false, true}) {
        auto cleared = dcmd("");
        cleared.retained = retained;
        node_.on_message(cleared);
    }
    EXPECT_TRUE(writes_.empty());
}

TEST_F(SparkplugPrimaryHostTest, BirthsWaitForThePrimaryHostToBeOnline) {
    EXPECT_EQ(publisher_.subscriptions.back(), "spBv1.0/STATE/scada");
    node_.next_will();
    node_.on_connected();
    first_datagram();
    EXPECT_TRUE(publisher_.published.empty());
    state(R"({"online":false,"timestamp":100})");
    state("not json");
    EXPECT_TRUE(publisher_.published.empty());
    state(R"({"online":true,"timestamp":200})");
    EXPECT_EQ(topics(), (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1",
                                                  "spBv1.0/plant1/DBIRTH/gw1/in"}));
    state(R"({"online":false,"timestamp":150})");  // older than the last: ignored
    EXPECT_EQ(publisher_.published.size(), 2u);
    state(R"({"online":false,"timestamp":300})");
    EXPECT_EQ(brokers_left_, 1);  // its NDEATH is the connection's will
    const std::vector<TagSample> changed{{0, Value{std::int64_t{9}}}};
    node_.tag_samples({consumed_, Quality::good, now_ms, false, changed});
    EXPECT_EQ(publisher_.published.size(), 2u);  // nothing while the host is away
    node_.next_will();
    node_.on_connected();
    state(R"({"online":true,"timestamp":400})");
    EXPECT_EQ(topics().at(2), "spBv1.0/plant1/NBIRTH/gw1");
    EXPECT_EQ(decoded(publisher_.published.at(3)).metrics(0).int_value(), 9u);
}

TEST_F(SparkplugPrimaryHostTest, ItsSessionSaysWhatItWaitsForAndWhatIsBorn) {
    const auto session = [this] {
        node_.refresh_session();
        return node_.stats().session;
    };
    EXPECT_EQ(session().bd_seq, std::nullopt);  // no will made yet
    EXPECT_EQ(session().primary_host_id, "scada");
    EXPECT_EQ(session().devices, 2u);
    node_.next_will();
    node_.on_connected();
    first_datagram();
    EXPECT_FALSE(session().born);  // the host is not online yet
    EXPECT_EQ(session().bd_seq, node_.bd_seq());
    state(R"({"online":true,"timestamp":200})");
    EXPECT_TRUE(session().host_online);
    EXPECT_TRUE(session().born);
    EXPECT_EQ(session().devices_born, 1u);  // the consumed one; the produced waits for values
}

TEST_F(SparkplugNodeTest, ARebirthRequestStopsDataUntilItsBirths) {
    node_.next_will();
    node_.on_connected();
    first_datagram();
    rebirth_request();  // answered at once
    publisher_.published.clear();
    rebirth_request();  // within the hold: waits for its end
    const std::vector<TagSample> changed{{0, Value{std::int64_t{9}}}};
    node_.tag_samples({consumed_, Quality::good, now_ms, false, changed});
    EXPECT_TRUE(publisher_.published.empty());  // no DDATA meanwhile
    advance(rebirth_hold);
    EXPECT_EQ(topics(), (std::vector<std::string>{"spBv1.0/plant1/NBIRTH/gw1",
                                                  "spBv1.0/plant1/DBIRTH/gw1/in"}));
    // The births carry the value the DDATA held back would have.
    EXPECT_EQ(decoded(publisher_.published.at(1)).metrics(0).int_value(), 9u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
