// /healthz, /readyz and the status API's pages served beside /metrics on the endpoint's own
// listener.

#include "adapters/metrics/detail/listener_routes.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "adapters/metrics/detail/event_stream.hpp"
#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::adapters::metrics {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using test::http_get;
using test::http_request;
using test::status_and_body;

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

/// Six clients that connect and say nothing, six that send half a request line and stop: two
/// of them (civetweb's two default workers, each waiting 30 s for its request) made 28 of 32
/// probes fail over a minute.
std::vector<std::unique_ptr<test::SilentClient>> slow_clients(std::uint16_t port) {
    std::vector<std::unique_ptr<test::SilentClient>> clients;
    for (int i = 0; i < 12; ++i) {
        clients.push_back(std::make_unique<test::SilentClient>(port, i % 2 ? "GET /heal" : ""));
    }
    return clients;
}

TEST(HealthPages, EveryProbeAnswersWhileSlowClientsHoldConnections) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    endpoint.update(snapshot(true, "ok"));
    const auto clients = slow_clients(endpoint.port());
    for (const auto& client : clients) ASSERT_TRUE(client->connected());
    // Probes for longer than the request timeout, so the slow clients' connections end (and
    // would be taken again by a client that reconnects) while probes go on.
    const auto until = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(detail::request_timeout_ms) + 1s;
    int probes = 0;
    while (probes < 10 || std::chrono::steady_clock::now() < until) {
        const auto answer = status_and_body(http_get(endpoint.port(), "/healthz"));
        ASSERT_EQ(answer, std::make_pair(std::string("200"), std::string("ok\n")))
            << "probe " << probes;
        ++probes;
        std::this_thread::sleep_for(100ms);
    }
}

TEST(HealthPages, AClientThatSendsNoRequestIsDisconnectedAfterTheRequestTimeout) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    const test::SilentClient silent(endpoint.port(), "");
    const test::SilentClient half(endpoint.port(), "GET /healthz HT");
    ASSERT_TRUE(silent.connected());
    ASSERT_TRUE(half.connected());
    // civetweb's default held them 30 s; the bound leaves room for a busy machine.
    EXPECT_TRUE(silent.closed_by_server(detail::request_timeout_ms + 8000));
    EXPECT_TRUE(half.closed_by_server(detail::request_timeout_ms + 8000));
}

TEST(StatusPages, AreServedUnderApiReadOnlyWithTheirSecurityHeaders) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/api/status")).first, "404");
    std::vector<std::string> asked;
    endpoint.serve_pages([&](std::string_view path) -> std::optional<HttpAnswer> {
        asked.emplace_back(path);
        if (path != "/api/status") return std::nullopt;
        return HttpAnswer{200, "application/json", R"({"up":true})"};
    });
    const auto response = http_get(endpoint.port(), "/api/status?x=1");
    EXPECT_EQ(status_and_body(response),
              std::make_pair(std::string("200"), std::string(R"({"up":true})")));
    for (const auto* header :
         {"Content-Type: application/json", "Cache-Control: no-store",
          "X-Content-Type-Options: nosniff", "X-Frame-Options: DENY",
          "Content-Security-Policy: default-src 'self'; frame-ancestors 'none'"}) {
        EXPECT_NE(response.find(header), std::string::npos) << header << " in " << response;
    }
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/api/nothing")).first, "404");
    // HEAD: the headers alone. Anything else is refused before the handler is asked.
    EXPECT_EQ(status_and_body(http_request(endpoint.port(), "HEAD", "/api/status")),
              std::make_pair(std::string("200"), std::string()));
    for (const auto* method : {"POST", "PUT", "DELETE"}) {
        const auto refused = http_request(endpoint.port(), method, "/api/status");
        EXPECT_EQ(status_and_body(refused).first, "405") << method;
        EXPECT_NE(refused.find("Allow: GET, HEAD"), std::string::npos) << refused;
    }
    EXPECT_EQ(asked, (std::vector<std::string>{"/api/status", "/api/nothing", "/api/status"}));
    // The health probes and the metrics are the listener's as before.
    endpoint.update(snapshot(true, "ok"));
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/healthz")).first, "200");
    EXPECT_NE(http_get(endpoint.port(), "/metrics").find("eip2mqtt_mqtt_connected 1"),
              std::string::npos);
    endpoint.serve_pages(nullptr);
    EXPECT_EQ(status_and_body(http_get(endpoint.port(), "/api/status")).first, "404");
}

TEST(EventStream, TheOpenParameterIsDecodedIntoNames) {
    EXPECT_EQ(detail::open_names(nullptr), std::vector<std::string>{});
    EXPECT_EQ(detail::open_names("x=1"), std::vector<std::string>{});
    EXPECT_EQ(detail::open_names("open=pump,turbine%201,,x%2Cy"),
              (std::vector<std::string>{"pump", "turbine 1", "x", "y"}));
}

TEST(EventStream, StreamsWhatItsSourceGivesUntilThePagesStop) {
    PrometheusEndpoint endpoint("127.0.0.1:0");
    std::atomic<int> batches{0};
    std::vector<std::string> asked_open;
    std::mutex mutex;
    endpoint.serve_pages([](std::string_view) { return std::optional<HttpAnswer>(); },
                         [&](const std::vector<std::string>& open) {
                             std::lock_guard lock(mutex);
                             asked_open = open;
                             return std::optional<std::string>(
                                 "event: beat\ndata: " + std::to_string(++batches) + "\n\n");
                         });
    const auto stream =
        test::http_read_until(endpoint.port(), "/api/events?open=a,b", "data: 2\n\n", 10000);
    EXPECT_NE(stream.find("Content-Type: text/event-stream"), std::string::npos) << stream;
    EXPECT_NE(stream.find("X-Frame-Options: DENY"), std::string::npos) << stream;
    EXPECT_NE(stream.find("event: beat\ndata: 1\n\nevent: beat\ndata: 2\n\n"), std::string::npos)
        << stream;
    {
        std::lock_guard lock(mutex);
        EXPECT_EQ(asked_open, (std::vector<std::string>{"a", "b"}));
    }
    // An open stream ends once the pages are no longer served.
    test::SilentClient page(endpoint.port(), "GET /api/events HTTP/1.0\r\n\r\n");
    ASSERT_TRUE(page.connected());
    EXPECT_EQ(status_and_body(http_request(endpoint.port(), "POST", "/api/events")).first, "405");
    endpoint.serve_pages(nullptr);
    EXPECT_TRUE(page.closed_by_server(10000));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::metrics
