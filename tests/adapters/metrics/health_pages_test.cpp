// /healthz and /readyz served beside /metrics on the endpoint's own listener.

#include "adapters/metrics/detail/health_pages.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::adapters::metrics {
namespace {

using namespace std::chrono_literals;
using test::http_get;

MetricsSnapshot snapshot(bool connected, const std::string& state) {
    MetricsSnapshot s;
    s.gateway.mqtt_connected = connected;
    ExchangeMetrics pump;
    pump.name = "pump";
    pump.direction = "consume";
    pump.state = state;
    s.exchanges.push_back(pump);
    return s;
}

/// The status line's code and the body of an HTTP response.
std::pair<std::string, std::string> status_and_body(const std::string& response) {
    const auto space = response.find(' ');
    const auto body = response.find("\r\n\r\n");
    if (space == std::string::npos || body == std::string::npos) return {"", response};
    return {response.substr(space + 1, 3), response.substr(body + 4)};
}

TEST(HealthPages, AnswerFromTheLastUpdateBesideTheMetrics) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/healthz")).first, "503");
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/readyz")).first, "503");

    endpoint.update(snapshot(true, "ok"));
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/healthz")),
              std::make_pair(std::string("200"), std::string("ok\n")));
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/readyz")),
              std::make_pair(std::string("200"), std::string("ready\n")));
    const auto metrics = http_get(endpoint.port(), "/metrics");
    EXPECT_NE(metrics.find("eip2mqtt_mqtt_connected 1"), std::string::npos) << metrics;

    endpoint.update(snapshot(false, "stale"));
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/healthz")).first, "200");
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/readyz")),
              std::make_pair(std::string("503"),
                             std::string("not ready: MQTT is not connected; exchange pump is "
                                         "stale\n")));
    const auto response = http_get(endpoint.port(), "/readyz");
    EXPECT_NE(response.find("Content-Type: text/plain"), std::string::npos) << response;
    EXPECT_NE(response.find("Cache-Control: no-store"), std::string::npos) << response;
}

TEST(HealthPages, HealthzFailsOnceUpdatesStop) {
    PrometheusEndpoint endpoint("127.0.0.1:0", 300ms);
    endpoint.update(snapshot(true, "ok"));
    // No more updates: the endpoint must say so within a bounded wait, whatever the load.
    std::pair<std::string, std::string> answer;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
        answer = status_and_body(http_get(endpoint.port(), "/healthz"));
        if (answer.first == "503") break;
        std::this_thread::sleep_for(50ms);
    }
    EXPECT_EQ(answer.first, "503");
    EXPECT_NE(answer.second.find("the gateway's loop has not reported for"), std::string::npos)
        << answer.second;
    endpoint.update(snapshot(true, "ok"));
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/healthz")).first, "200");
}

}  // namespace
}  // namespace eip2mqtt::adapters::metrics
