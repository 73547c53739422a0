#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tests/support/http_get.hpp"

namespace eip2mqtt::adapters::metrics {
namespace EIP2MQTT_THIS_FILE {

using test::http_get;

bool has_line(const std::string& text, const std::string& line) {
    return ("\n" + text + "\n").find("\n" + line + "\n") != std::string::npos;
}

MetricsSnapshot snapshot(std::uint64_t received) {
    MetricsSnapshot s;
    ExchangeMetrics turbine;
    turbine.name = "turbine1";
    turbine.direction = "consume";
    turbine.state = "ok";
    turbine.consumed.received = received;
    turbine.consumed.accepted = received - 2;
    turbine.consumed.missed = 3;
    turbine.consumed.duplicates = 1;
    turbine.last_seen_age_seconds = 0.25;
    turbine.jitter_seconds = 0.002;
    turbine.mean_period_seconds = 0.1;
    s.exchanges.push_back(turbine);

    ExchangeMetrics idle;
    idle.name = "idle";
    idle.direction = "consume";
    idle.state = "waiting";
    s.exchanges.push_back(idle);

    ExchangeMetrics setpoints;
    setpoints.name = "setpoints";
    setpoints.direction = "produce";
    setpoints.state = "producing";
    setpoints.produced.sent = 17;
    setpoints.produced.save_failures = 2;
    setpoints.image_saved = false;
    s.exchanges.push_back(setpoints);

    s.gateway.datagrams = received + 5;
    s.gateway.accepted = received - 2;
    s.gateway.dropped = {{"too_short", 4}, {"unknown_exchange", 1}};
    s.gateway.mqtt_connected = true;
    s.gateway.mqtt_broker = "tcp://broker-b:1883";
    s.gateway.published = 99;
    s.gateway.buffered = 7;
    s.gateway.writes.writes_ok = 2;
    s.gateway.writes.writes_rejected[static_cast<std::size_t>(core::write::WriteError::above_max)] =
        1;
    s.gateway.writes.writes_cancelled = 3;
    s.gateway.writes.image_saves = {2, 4, 1};
    return s;
}

TEST(PrometheusEndpoint, ServesTheSnapshotInTextFormat) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    ASSERT_NE(endpoint.port(), 0);
    endpoint.update(snapshot(42));

    const auto page = http_get(endpoint.port(), "/metrics");
    ASSERT_NE(page.find("200 OK"), std::string::npos) << page;
    for (
        const auto* line : {
            "# TYPE eip2mqtt_exchange_received_total counter",
            R"(eip2mqtt_exchange_received_total{direction="consume",exchange="turbine1"} 42)",
            R"(eip2mqtt_exchange_accepted_total{direction="consume",exchange="turbine1"} 40)",
            R"(eip2mqtt_exchange_missed_total{direction="consume",exchange="turbine1"} 3)",
            R"(eip2mqtt_exchange_duplicates_total{direction="consume",exchange="turbine1"} 1)",
            "# TYPE eip2mqtt_exchange_state gauge",
            R"(eip2mqtt_exchange_state{direction="consume",exchange="turbine1",state="ok"} 1)",
            R"(eip2mqtt_exchange_state{direction="consume",exchange="turbine1",state="stale"} 0)",
            R"(eip2mqtt_exchange_state{direction="consume",exchange="idle",state="waiting"} 1)",
            R"(eip2mqtt_exchange_state{direction="produce",exchange="setpoints",state="producing"} 1)",
            R"(eip2mqtt_exchange_state{direction="produce",exchange="setpoints",state="paused"} 0)",
            R"(eip2mqtt_exchange_last_seen_age_seconds{direction="consume",exchange="turbine1"} 0.25)",
            R"(eip2mqtt_exchange_jitter_seconds{direction="consume",exchange="turbine1"} 0.002)",
            R"(eip2mqtt_exchange_mean_period_seconds{direction="consume",exchange="turbine1"} 0.1)",
            R"(eip2mqtt_exchange_sent_total{direction="produce",exchange="setpoints"} 17)",
            "eip2mqtt_datagrams_total 47",
            "eip2mqtt_datagrams_accepted_total 40",
            R"(eip2mqtt_datagrams_dropped_total{reason="too_short"} 4)",
            R"(eip2mqtt_datagrams_dropped_total{reason="unknown_exchange"} 1)",
            "# TYPE eip2mqtt_mqtt_connected gauge",
            "eip2mqtt_mqtt_connected 1",
            "# TYPE eip2mqtt_mqtt_broker gauge",
            R"(eip2mqtt_mqtt_broker{url="tcp://broker-b:1883"} 1)",
            "eip2mqtt_mqtt_published_total 99",
            "eip2mqtt_mqtt_buffered 7",
            "eip2mqtt_mqtt_publications_dropped_total 0",
            "eip2mqtt_writes_ok_total 2",
            R"(eip2mqtt_writes_rejected_total{reason="above_max"} 1)",
            "eip2mqtt_writes_cancelled_total 3",
            R"(eip2mqtt_exchange_save_failures_total{direction="produce",exchange="setpoints"} 2)",
            R"(eip2mqtt_exchange_image_saved{direction="produce",exchange="setpoints"} 0)",
            "eip2mqtt_writes_not_saved_total 4",
            "eip2mqtt_writes_sent_unsaved_total 1",
            "eip2mqtt_image_save_failures_total 2",
        }) {
        EXPECT_TRUE(has_line(page, line)) << "missing: " << line << "\nin:\n" << page;
    }
    // Unknown gauges are absent rather than a made-up value; counters follow the direction.
    EXPECT_EQ(
        page.find(
            R"(eip2mqtt_exchange_last_seen_age_seconds{direction="consume",exchange="idle"})"),
        std::string::npos);
    EXPECT_EQ(page.find(R"(eip2mqtt_exchange_received_total{direction="produce")"),
              std::string::npos);
    EXPECT_EQ(page.find(R"(eip2mqtt_exchange_sent_total{direction="consume")"), std::string::npos);
}

TEST(PrometheusEndpoint, TheCommandResponderHasItsFamiliesOnlyWhenEnabled) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    auto s = snapshot(42);
    endpoint.update(s);
    EXPECT_EQ(http_get(endpoint.port(), "/metrics").find("eip2mqtt_commands_"), std::string::npos);

    using core::command::DecodeError;
    using core::command::PduType;
    core::command::CommandCounters commands;
    commands.requests[request_index(PduType::read_request)] = 5;
    commands.requests[request_index(PduType::summary_request)] = 2;
    commands.errors = 1;
    commands.refused = 3;
    commands.dropped = 190;
    commands.dropped_per_source = 150;
    commands.challenged = 7;
    commands.naks[static_cast<std::size_t>(DecodeError::malformed)] = 4;
    commands.ignored = 6;
    s.gateway.commands = commands;
    endpoint.update(s);
    const auto page = http_get(endpoint.port(), "/metrics");
    for (const auto* line : {
             R"(eip2mqtt_commands_requests_total{type="read"} 5)",
             R"(eip2mqtt_commands_requests_total{type="summary"} 2)",
             "eip2mqtt_commands_errors_total 1",
             "eip2mqtt_commands_refused_total 3",
             "eip2mqtt_commands_dropped_total 190",
             "eip2mqtt_commands_dropped_per_source_total 150",
             "eip2mqtt_commands_challenged_total 7",
             R"(eip2mqtt_commands_naks_total{reason="malformed"} 4)",
             "eip2mqtt_commands_ignored_total 6",
         }) {
        EXPECT_TRUE(has_line(page, line)) << "missing: " << line << "\nin:\n" << page;
    }
}

TEST(PrometheusEndpoint, SeveralConnectionsHaveASeriesEachLabelledByName) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    auto s = snapshot(42);
    endpoint.update(s);
    EXPECT_EQ(http_get(endpoint.port(), "/metrics").find("eip2mqtt_connection_"),
              std::string::npos);
    s.gateway.connections = {{"site", true, "tcp://a:1883", 10, 0, 0, 0, std::nullopt},
                             {"enterprise", false, "", 4, 6, 1, 0, HistoryMetrics{}}};
    s.gateway.connections[1].history->journaled = 6;
    endpoint.update(s);
    const auto page = http_get(endpoint.port(), "/metrics");
    for (const auto* line : {
             R"(eip2mqtt_connection_mqtt_connected{connection="site"} 1)",
             R"(eip2mqtt_connection_mqtt_connected{connection="enterprise"} 0)",
             R"(eip2mqtt_connection_mqtt_published_total{connection="site"} 10)",
             R"(eip2mqtt_connection_mqtt_buffered{connection="enterprise"} 6)",
             R"(eip2mqtt_connection_mqtt_publications_dropped_total{connection="enterprise"} 1)",
             R"(eip2mqtt_connection_history_journaled_total{connection="enterprise"} 6)",
         }) {
        EXPECT_TRUE(has_line(page, line)) << "missing: " << line << "\nin:\n" << page;
    }
    // A connection without a journal has no journal series.
    EXPECT_EQ(page.find(R"(eip2mqtt_connection_history_entries{connection="site"})"),
              std::string::npos);
}

TEST(PrometheusEndpoint, AnUpdateReplacesTheValues) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    endpoint.update(snapshot(42));
    ASSERT_TRUE(has_line(
        http_get(endpoint.port(), "/metrics"),
        R"(eip2mqtt_exchange_received_total{direction="consume",exchange="turbine1"} 42)"));

    auto next = snapshot(1000);
    next.exchanges[0].state = "stale";
    next.exchanges.pop_back();  // an exchange removed by a reload disappears
    next.gateway.mqtt_connected = false;
    next.gateway.mqtt_broker.clear();
    endpoint.update(next);
    const auto page = http_get(endpoint.port(), "/metrics");
    for (const auto* line : {
             R"(eip2mqtt_exchange_received_total{direction="consume",exchange="turbine1"} 1000)",
             R"(eip2mqtt_exchange_state{direction="consume",exchange="turbine1",state="ok"} 0)",
             R"(eip2mqtt_exchange_state{direction="consume",exchange="turbine1",state="stale"} 1)",
             "eip2mqtt_mqtt_connected 0",
             "eip2mqtt_datagrams_total 1005",
         }) {
        EXPECT_TRUE(has_line(page, line)) << "missing: " << line << "\nin:\n" << page;
    }
    EXPECT_EQ(page.find("setpoints"), std::string::npos) << page;
    EXPECT_EQ(page.find("eip2mqtt_mqtt_broker"), std::string::npos) << page;  // disconnected
}

TEST(PrometheusEndpoint, ServesAnEmptyPageBeforeTheFirstUpdate) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    const auto page = http_get(endpoint.port(), "/metrics");
    EXPECT_NE(page.find("200 OK"), std::string::npos) << page;
    EXPECT_EQ(page.find("eip2mqtt_"), std::string::npos) << page;
}

TEST(PrometheusEndpoint, APortInUseIsAClearStartUpError) {
    PrometheusEndpoint first("127.0.0.1:0");
    const std::string taken = "127.0.0.1:" + std::to_string(first.port());
    try {
        PrometheusEndpoint second(taken);
        FAIL() << "listened twice on " << taken;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot listen for metrics on " + taken),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::metrics
