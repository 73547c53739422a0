// What /healthz and /readyz answer, with time as an argument.

#include "eip2mqtt/adapters/metrics/health.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::adapters::metrics {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using Clock = HealthState::Clock;

const Clock::time_point t0{};

ExchangeMetrics exchange(std::string name, std::string state) {
    ExchangeMetrics e;
    e.name = std::move(name);
    e.direction = "consume";
    e.state = std::move(state);
    return e;
}

MetricsSnapshot snapshot(bool connected, std::vector<ExchangeMetrics> exchanges) {
    MetricsSnapshot s;
    s.gateway.mqtt_connected = connected;
    s.exchanges = std::move(exchanges);
    return s;
}

TEST(HealthState, NeitherLiveNorReadyBeforeTheLoopReports) {
    const HealthState health(10s);
    EXPECT_EQ(health.liveness(t0).status, 503);
    EXPECT_EQ(health.liveness(t0).body, "starting: the gateway's loop has not reported yet\n");
    EXPECT_EQ(health.readiness(t0).status, 503);
}

TEST(HealthState, ConnectedAndFreshIsReady) {
    HealthState health(10s);
    health.update(snapshot(true, {exchange("pump", "ok"), exchange("idle", "waiting"),
                                  exchange("sp", "producing")}),
                  t0);
    EXPECT_EQ(health.liveness(t0 + 1s).status, 200);
    EXPECT_EQ(health.liveness(t0 + 1s).body, "ok\n");
    EXPECT_EQ(health.readiness(t0 + 1s).status, 200);
    EXPECT_EQ(health.readiness(t0 + 1s).body, "ready\n");
}

TEST(HealthState, WithSeveralConnectionsEachOneDownIsNamed) {
    HealthState health(10s);
    auto s = snapshot(true, {exchange("pump", "ok")});
    s.gateway.connections = {{"site", true, "tcp://a:1883", 0, 0, 0, 0, std::nullopt},
                             {"enterprise", false, "", 0, 0, 0, 0, std::nullopt}};
    health.update(s, t0);
    EXPECT_EQ(health.readiness(t0).body,
              "not ready: MQTT connection enterprise is not connected\n");
    s.gateway.connections[0].connected = false;
    health.update(s, t0);
    EXPECT_EQ(health.readiness(t0).body,
              "not ready: MQTT connection site, enterprise are not connected\n");
    s.gateway.connections[0].connected = s.gateway.connections[1].connected = true;
    health.update(s, t0);
    EXPECT_EQ(health.readiness(t0).status, 200);
}

TEST(HealthState, NotConnectedOrStaleIsLiveButNotReadyAndSaysWhy) {
    HealthState health(10s);
    health.update(snapshot(false, {exchange("pump", "ok")}), t0);
    EXPECT_EQ(health.liveness(t0).status, 200);
    EXPECT_EQ(health.readiness(t0).status, 503);
    EXPECT_EQ(health.readiness(t0).body, "not ready: MQTT is not connected\n");

    health.update(snapshot(true, {exchange("pump", "stale"), exchange("fan", "ok")}), t0);
    EXPECT_EQ(health.readiness(t0).body, "not ready: exchange pump is stale\n");

    health.update(snapshot(false, {exchange("pump", "stale"), exchange("fan", "stale")}), t0);
    EXPECT_EQ(health.readiness(t0).body,
              "not ready: MQTT is not connected; exchanges pump, fan are stale\n");

    health.update(snapshot(true, {exchange("pump", "ok")}), t0);
    EXPECT_EQ(health.readiness(t0).status, 200);
}

TEST(HealthState, ManyStaleExchangesAreCountedPastTen) {
    std::vector<ExchangeMetrics> exchanges;
    for (int i = 0; i < 12; ++i) exchanges.push_back(exchange("e" + std::to_string(i), "stale"));
    HealthState health(10s);
    health.update(snapshot(true, exchanges), t0);
    EXPECT_EQ(health.readiness(t0).body,
              "not ready: exchanges e0, e1, e2, e3, e4, e5, e6, e7, e8, e9 and 2 more are stale\n");
}

TEST(HealthState, ALoopThatStopsReportingIsNeitherLiveNorReady) {
    HealthState health(10s);
    health.update(snapshot(true, {exchange("pump", "ok")}), t0);
    EXPECT_EQ(health.liveness(t0 + 10s).status, 200);
    const auto late = health.liveness(t0 + 12500ms);
    EXPECT_EQ(late.status, 503);
    EXPECT_EQ(late.body, "the gateway's loop has not reported for 12.5 s (limit 10.0 s)\n");
    EXPECT_EQ(health.readiness(t0 + 12500ms).body, late.body);
    health.update(snapshot(true, {exchange("pump", "ok")}), t0 + 13s);
    EXPECT_EQ(health.liveness(t0 + 13s).status, 200);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::metrics
