// The gateway's metrics from its counters alone (docs/mqtt-api.md "Metrics"): each counter lands
// in its own field, every drop reason and write error is listed even at zero, and the payload
// is one the documented schema accepts.

#include "eip2mqtt/app/health/metrics.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::wire::DropReason;
using core::write::WriteError;
using nlohmann::json;

struct Counters {
    DatagramCounters datagrams;
    WriteCounters writes;
    adapters::mqtt::ClientStats mqtt;

    Counters() {
        datagrams.datagrams = 10;
        datagrams.accepted = 6;
        datagrams.dropped[static_cast<std::size_t>(DropReason::too_short)] = 3;
        datagrams.dropped[static_cast<std::size_t>(DropReason::wrong_source)] = 1;
        writes.writes_ok = 5;
        writes.writes_cancelled = 2;
        writes.image_saves = {13, 14, 15};
        writes.writes_rejected[static_cast<std::size_t>(WriteError::out_of_range)] = 4;
        mqtt.connected = true;
        mqtt.published = 100;
        mqtt.queued = 7;
        mqtt.dropped_overflow = 8;
        mqtt.coalesced = 9;
        mqtt.refused = 11;
        mqtt.connects = 12;
        mqtt.broker = "tcp://broker-b:1883";
    }
    MetricsSources sources() const { return {datagrams, writes, mqtt}; }
};

TEST(MetricsJson, EachCounterLandsInItsField) {
    const Counters c;
    const auto metrics = json::parse(northbound::json_tree::metrics_json(c.sources(), 42s));
    EXPECT_EQ(metrics["uptime_s"], 42);
    EXPECT_EQ(metrics["datagrams"], 10);
    EXPECT_EQ(metrics["accepted"], 6);
    EXPECT_EQ(metrics["dropped"]["too_short"], 3);
    EXPECT_EQ(metrics["dropped"]["wrong_source"], 1);
    EXPECT_EQ(metrics["published"], 100);
    EXPECT_EQ(metrics["buffered"], 7);
    EXPECT_EQ(metrics["publications_dropped"], 8);
    EXPECT_EQ(metrics["publications_coalesced"], 9);
    EXPECT_EQ(metrics["publications_refused"], 11);
    EXPECT_EQ(metrics["mqtt_connects"], 12);
    EXPECT_EQ(metrics["broker"], "tcp://broker-b:1883");
    EXPECT_EQ(metrics["writes_ok"], 5);
    EXPECT_EQ(metrics["writes_cancelled"], 2);
    EXPECT_EQ(metrics["writes_rejected"]["out_of_range"], 4);
    EXPECT_EQ(metrics["image_save_failures"], 13);
    EXPECT_EQ(metrics["writes_not_saved"], 14);
    EXPECT_EQ(metrics["writes_sent_unsaved"], 15);
}

TEST(MetricsJson, EveryDropReasonAndWriteErrorIsListedEvenAtZero) {
    const auto metrics = json::parse(northbound::json_tree::metrics_json(Counters{}.sources(), 0s));
    ASSERT_EQ(metrics["dropped"].size(), core::wire::drop_reason_count);
    for (const auto reason : core::wire::all_drop_reasons) {
        EXPECT_TRUE(metrics["dropped"].contains(std::string(core::wire::to_string(reason))));
    }
    ASSERT_EQ(metrics["writes_rejected"].size(), core::write::write_error_count);
    EXPECT_EQ(metrics["writes_rejected"]["overlapping_tags"], 0);
}

TEST(MetricsJson, MatchesTheDocumentedSchema) {
    const auto payload = northbound::json_tree::metrics_json(Counters{}.sources(), 42s);
    EXPECT_EQ(test::schema_problem(test::schema_file("metrics.json"), payload), "") << payload;
}

TEST(MetricsSnapshot, CarriesTheGatewayFiguresAndEachExchange) {
    const Counters c;
    core::plan::ExchangeSpec spec;
    spec.name = "e1";
    spec.direction = core::plan::Direction::consume;
    spec.exchange_id = 1;
    spec.length = 4;
    spec.topic = "e1";
    test::RecordingNorthbound northbound;
    std::vector<std::unique_ptr<ExchangeConsumer>> consumers;
    consumers.push_back(std::make_unique<ExchangeConsumer>(
        core::plan::make_exchange_plan(spec, "plant"), northbound));

    const auto snapshot = metrics_snapshot(c.sources(), consumers, {}, core::MonoTime{} + 1h);
    EXPECT_EQ(snapshot.gateway.datagrams, 10u);
    EXPECT_EQ(snapshot.gateway.accepted, 6u);
    EXPECT_EQ(snapshot.gateway.dropped.at("too_short"), 3u);
    EXPECT_TRUE(snapshot.gateway.mqtt_connected);
    EXPECT_EQ(snapshot.gateway.mqtt_broker, "tcp://broker-b:1883");
    EXPECT_EQ(snapshot.gateway.published, 100u);
    EXPECT_EQ(snapshot.gateway.publications_refused, 11u);
    const auto& writes = snapshot.gateway.writes;
    EXPECT_EQ(writes.writes_rejected[static_cast<std::size_t>(WriteError::out_of_range)], 4u);
    EXPECT_EQ(writes.image_saves.failures, 13u);
    EXPECT_EQ(writes.image_saves.writes_not_saved, 14u);
    EXPECT_EQ(writes.image_saves.writes_sent_unsaved, 15u);
    ASSERT_EQ(snapshot.exchanges.size(), 1u);
    EXPECT_EQ(snapshot.exchanges[0].name, "e1");
    EXPECT_EQ(snapshot.exchanges[0].direction, "consume");
    EXPECT_EQ(snapshot.exchanges[0].state, "waiting");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

TEST(HistoryMetrics, TheJournalsFiguresWithTheOldestEntrysAge) {
    const Counters counters;
    history::HistoryStats stats;
    stats.journal = {1200, 65536, 3, 1700000000000};
    stats.journaled = 1500;
    stats.replayed = 297;
    stats.discarded = 1;
    stats.replaying = true;
    stats.taken_at_ms = 1700000012500;
    const auto h = history_metrics(stats);
    EXPECT_EQ(h.entries, 1200u);
    EXPECT_EQ(h.bytes, 65536u);
    EXPECT_EQ(h.dropped, 3u);
    EXPECT_DOUBLE_EQ(h.oldest_age_seconds, 12.5);
    EXPECT_TRUE(h.replaying);
    stats.journal.oldest_timestamp_ms.reset();  // empty: no age
    EXPECT_DOUBLE_EQ(history_metrics(stats).oldest_age_seconds, 0);

    // On the metrics topic, and as its schema says.
    MetricsSources sources = counters.sources();
    sources.history = &stats;
    const auto payload = northbound::json_tree::metrics_json(sources, 42s);
    const auto m = json::parse(payload);
    EXPECT_EQ(m["history_dropped"], 3);
    EXPECT_EQ(m["history"]["entries"], 1200);
    EXPECT_EQ(m["history"]["replayed"], 297);
    EXPECT_EQ(test::schema_problem(test::schema_file("metrics.json"), payload), "") << payload;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
