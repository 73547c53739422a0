// The status API's documents from running exchanges: each exchange's line (its `_status` as the
// MQTT topic has it, its age and rate), each tag's sample in engineering units, names escaped,
// and nothing for an exchange that does not run. The loop never runs: datagrams are routed by
// hand and the time is a fake clock's.

#include "eip2mqtt/app/status/status_documents.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <nlohmann/json.hpp>

#include "tests/app/support/test_exchanges.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::app::status {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::Direction;
using core::plan::TagType;
using json = nlohmann::json;

class StatusDocumentsTest : public ::testing::Test {
protected:
    StatusDocumentsTest() {
        auto speed = test::test_tag("SPEED", 0, TagType::dint);
        speed.mutable_extras().unit = "rpm";
        core::plan::Scaling scale;
        scale.raw = {0, 1000};
        scale.eu = {0, 100};
        speed.mutable_extras().scale = scale;
        std::vector<core::plan::ExchangePlan> plans;
        plans.push_back(test::test_plan("pump \"1\"", Direction::consume, 8,
                                        {speed, test::test_tag("FLOW", 4, TagType::real)}));
        plans.push_back(test::test_exchange("cmd", Direction::produce, 2,
                                            test::test_tag("SP", 0, TagType::dint, true)));
        exchanges_->apply(std::move(plans), clock_.monotonic(), clock_.wall());
        facts_.id = "gw";
        facts_.config_file = "/etc/eip2mqtt/eip2mqtt.yaml";
        facts_.brokers = {"tcp://a:1883", "tcp://b:1883"};
        facts_.started_at = facts_.loaded_at = clock_.wall();
        facts_.started_mono = clock_.monotonic();
    }
    void receive(std::uint16_t request_id, std::int64_t speed) {
        const auto datagram = test::DatagramBuilder("10.0.0.1", 1, 8)
                                  .request_id(request_id)
                                  .set("0.0", TagType::dint, speed)
                                  .set("4.0", TagType::real, 1.5)
                                  .build();
        exchanges_->route(datagram, {0x0A000001, 18246}, false, clock_.monotonic());
    }
    json status() {
        const MetricsSources sources{exchanges_->datagram_counters(), writes_, mqtt_};
        return json::parse(
            status_document(facts_, sources, *exchanges_, clock_.monotonic(), clock_.wall()));
    }
    json exchange(std::string_view name) {
        const auto text = exchange_document(*exchanges_, name, clock_.monotonic(), clock_.wall());
        return text ? json::parse(*text) : json();
    }

    boost::asio::io_context loop_;
    test::FakeClock clock_;
    test::TestExchanges exchanges_{loop_, clock_, "eip2mqtt_status_documents"};
    GatewayFacts facts_;
    core::write::WriteCounters writes_;
    adapters::mqtt::ClientStats mqtt_;
};

TEST_F(StatusDocumentsTest, TheGatewayAndEachExchangeInOneLineWithoutTags) {
    mqtt_.connected = true;
    mqtt_.broker = "tcp://b:1883";
    mqtt_.connects = 2;
    mqtt_.connection_losses = 1;
    clock_.advance(90s);
    const auto doc = status();
    EXPECT_EQ(doc["gateway"]["id"], "gw");
    EXPECT_EQ(doc["gateway"]["config"]["file"], "/etc/eip2mqtt/eip2mqtt.yaml");
    EXPECT_EQ(doc["gateway"]["mqtt"]["brokers"],
              json::parse(R"([{"url":"tcp://a:1883","connected":false},)"
                          R"({"url":"tcp://b:1883","connected":true}])"));
    EXPECT_EQ(doc["gateway"]["mqtt"]["connected"], true);
    EXPECT_EQ(doc["gateway"]["mqtt"]["connects"], 2);
    EXPECT_EQ(doc["gateway"]["mqtt"]["connection_losses"], 1);
    EXPECT_TRUE(doc["gateway"]["sparkplug"].is_null());
    EXPECT_EQ(doc["gateway"]["metrics"]["uptime_s"], 90);
    EXPECT_EQ(doc["gateway"]["time"].get<std::int64_t>() -
                  doc["gateway"]["started_at"].get<std::int64_t>(),
              90000);
    ASSERT_EQ(doc["exchanges"].size(), 2u);
    const auto& pump = doc["exchanges"][0];
    EXPECT_EQ(pump["name"], "pump \"1\"");
    EXPECT_EQ(pump["direction"], "consume");
    EXPECT_EQ(pump["topic"], "acme/pump \"1\"");
    EXPECT_EQ(pump["producer"], "10.0.0.1");
    EXPECT_EQ(pump["tag_count"], 2);
    EXPECT_EQ(pump["status"]["state"], "waiting");
    EXPECT_TRUE(pump["last_seen_age_ms"].is_null());
    EXPECT_FALSE(pump.contains("tags"));
    const auto& cmd = doc["exchanges"][1];
    EXPECT_EQ(cmd["direction"], "produce");
    EXPECT_EQ(cmd["destination"], "127.0.0.1");
    EXPECT_EQ(cmd["status"]["state"], "producing");
}

TEST_F(StatusDocumentsTest, TheSparkplugSessionAsTheNodeLastSaidIt) {
    northbound::sparkplug::SparkplugStats stats;
    stats.node_births = 3;
    stats.session = {"plant", "gw", "scada", true, true, 7, 2, 1};
    MetricsSources sources{exchanges_->datagram_counters(), writes_, mqtt_};
    sources.sparkplug = &stats;
    const auto doc = json::parse(
        status_document(facts_, sources, *exchanges_, clock_.monotonic(), clock_.wall()));
    EXPECT_EQ(doc["gateway"]["sparkplug"],
              json::parse(R"({"group_id":"plant","edge_node_id":"gw","primary_host":"scada",)"
                          R"("host_online":true,"born":true,"bd_seq":7,"devices":2,)"
                          R"("devices_born":1,"node_births":3,"rebirth_requests":0})"));
    // No primary host: none named, no state of one; no will yet: no bdSeq.
    stats.session = {"plant", "gw", "", false, false, std::nullopt, 2, 0};
    const auto before = json::parse(
        status_document(facts_, sources, *exchanges_, clock_.monotonic(), clock_.wall()));
    EXPECT_TRUE(before["gateway"]["sparkplug"]["primary_host"].is_null());
    EXPECT_TRUE(before["gateway"]["sparkplug"]["host_online"].is_null());
    EXPECT_TRUE(before["gateway"]["sparkplug"]["bd_seq"].is_null());
    EXPECT_EQ(before["gateway"]["sparkplug"]["born"], false);
}

TEST_F(StatusDocumentsTest, SeveralConnectionsAreListedEachWithItsState) {
    EXPECT_EQ(status()["gateway"]["connections"], json::array());  // one connection: none
    mqtt_.connected = true;
    mqtt_.broker = "tcp://a:1883";
    mqtt_.published = 12;
    history::HistoryStats journal;
    journal.journal.entries = 40;
    MetricsSources sources{exchanges_->datagram_counters(), writes_, mqtt_};
    sources.mqtt_name = "site";
    adapters::mqtt::ClientStats enterprise;
    enterprise.queued = 5;
    sources.more_connections.push_back({"enterprise", enterprise, &journal});
    const auto doc = json::parse(
        status_document(facts_, sources, *exchanges_, clock_.monotonic(), clock_.wall()));
    EXPECT_EQ(doc["gateway"]["connections"],
              json::parse(R"([{"name":"site","connected":true,"broker":"tcp://a:1883",)"
                          R"("published":12,"buffered":0,"journaled":null},)"
                          R"({"name":"enterprise","connected":false,"broker":"",)"
                          R"("published":0,"buffered":5,"journaled":40}])"));
}

TEST_F(StatusDocumentsTest, TheLastWritesAndWarningsFollowWhenGiven) {
    EXPECT_FALSE(status().contains("writes"));
    WriteLog log;
    const auto id = log.arrived({{"r", "", nullptr, WriteOrigin::mqtt},
                                 "acme/cmd/SP/set",
                                 core::write::WriteRejection{core::write::WriteError::empty, ""},
                                 {}},
                                clock_.wall());
    log.answered(id, "empty", clock_.wall());
    const std::vector<std::string> warnings{"2026-11-30T16:00:00.000Z warning: \"quoted\""};
    const MetricsSources sources{exchanges_->datagram_counters(), writes_, mqtt_};
    const auto doc = json::parse(status_document(facts_, sources, *exchanges_, clock_.monotonic(),
                                                 clock_.wall(), &log, warnings));
    ASSERT_EQ(doc["writes"].size(), 1u);
    EXPECT_EQ(doc["writes"][0]["target"], "acme/cmd/SP/set");
    EXPECT_EQ(doc["writes"][0]["result"], "empty");
    EXPECT_EQ(doc["warnings"], json(warnings));
}

TEST_F(StatusDocumentsTest, AConsumedExchangesTagsInEngineeringUnitsAndItsAge) {
    // Before a datagram: the tags are there, without a sample.
    auto pump = exchange("pump \"1\"");
    ASSERT_EQ(pump["tags"].size(), 2u);
    EXPECT_TRUE(pump["tags"][0]["sample"].is_null());
    receive(1, 500);
    receive(3, 750);
    clock_.advance(1500ms);
    pump = exchange("pump \"1\"");
    EXPECT_EQ(pump["status"]["state"], "ok");
    EXPECT_EQ(pump["status"]["accepted"], 2);
    EXPECT_EQ(pump["status"]["missed"], 1);
    EXPECT_EQ(pump["last_seen_age_ms"], 1500);
    const auto& speed = pump["tags"][0];
    EXPECT_EQ(speed["name"], "SPEED");
    EXPECT_EQ(speed["type"], "dint");
    EXPECT_EQ(speed["unit"], "rpm");
    EXPECT_EQ(speed["topic"], "acme/pump \"1\"/SPEED");
    EXPECT_EQ(speed["sample"]["value"], 75.0);  // 750 of 0..1000 raw is 75 of 0..100
    EXPECT_EQ(speed["sample"]["quality"], "good");
    EXPECT_FALSE(pump["tags"][1].contains("unit"));
    EXPECT_EQ(pump["tags"][1]["sample"]["value"], 1.5);
}

TEST_F(StatusDocumentsTest, AProducedExchangesValuesAndNothingForAnUnknownName) {
    const auto cmd = exchange("cmd");
    EXPECT_EQ(cmd["direction"], "produce");
    ASSERT_EQ(cmd["tags"].size(), 1u);
    EXPECT_EQ(cmd["tags"][0]["sample"]["value"], 0);
    EXPECT_FALSE(exchange_document(*exchanges_, "nothing", clock_.monotonic(), clock_.wall()));
    EXPECT_FALSE(exchange_document(*exchanges_, "pump", clock_.monotonic(), clock_.wall()));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::status
