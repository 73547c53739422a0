// Store and forward with the real binary, a real Mosquitto and real UDP: a counter
// at 100 datagrams a second through broker outages, a gateway killed in the middle of one, a
// reconnect during the replay, the journal's bound and a damaged journal file. A subscriber of
// `_values` and `_history` together sees every counter value exactly once.

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/store_and_forward_fixture.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr const char* kEnabled = "    enabled: true\n    replay_rate: 500\n";

TEST_F(StoreAndForwardTest, ABrokerOutageOfTenSecondsLeavesNoGapAndNoDuplicate) {
    start_gateway_with(kEnabled);
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 10s));

    stop_broker();
    std::this_thread::sleep_for(10s);  // the scenario: the broker stays down, traffic goes on
    const auto from = recorder_->count();
    const auto last = end_outage_once_live_again();
    EXPECT_TRUE(wait_all_received(last)) << gateway_->output();
    expect_each_value_once(last);

    // The history is marked as such, and not retained.
    const auto history = recorder_->messages_on(topic("line/_history"));
    ASSERT_GE(history.size(), 500u);  // 10 s at 100 a second went there
    for (const auto& m : history) {
        EXPECT_FALSE(m.retained);
        EXPECT_EQ(m.user_properties,
                  (std::vector<std::pair<std::string, std::string>>{{"historical", "true"}}));
    }
    // Once replayed, the journal is empty again, and the metrics say what went through it.
    const auto metrics = recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& p) {
            const auto m = json::parse(p);
            return m.contains("history") && m["history"]["entries"] == 0 &&
                   m["history"]["replayed"].get<int>() > 0;
        },
        15s, from);
    ASSERT_TRUE(metrics.has_value());
    const auto m = json::parse(metrics->payload);
    EXPECT_EQ(m["history"]["replayed"], m["history"]["journaled"]);
    EXPECT_EQ(m["history_dropped"], 0);

    // The payloads are those docs/mqtt-api.md documents: `_history` has the `_values` schema.
    std::vector<SchemaCheck> checks{{schema_file("metrics.json"), metrics->payload}};
    for (std::size_t i = 0; i < history.size(); i += 50) {
        checks.push_back({schema_file("values.json"), history[i].payload});
    }
    for (const auto& problem : schema_problems(checks)) EXPECT_EQ(problem, "");
}

TEST_F(StoreAndForwardTest, AGatewayKilledDuringTheOutageReplaysWhatItJournaled) {
    start_gateway_with(kEnabled, true);
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 10s));
    // Between the broker's stop and the gateway noticing it, values go to the client's queue
    // (in memory, like any live publication); a killed process loses those. The counter pauses
    // over that moment, so that every value sent is either delivered or journaled.
    pause_when_delivered();
    stop_broker();
    counter_->resume();
    // The scenario: the outage goes on, for 250 journaled datagrams (3 s at 100 a second on an
    // idle machine; counted, not timed, since a loaded one sends fewer in 3 s).
    EXPECT_TRUE(wait_metric(
        "eip2mqtt_history_journaled_total", [](double v) { return v >= 250; }, 30s));
    const auto before_kill = counter_->pause();
    // Every datagram sent is accepted, and every entry journaled is committed (the journal's
    // figures count committed entries only).
    ASSERT_TRUE(wait_metric("eip2mqtt_datagrams_accepted_total", [&](double v) {
        return v >= static_cast<double>(before_kill);
    })) << http_get(prometheus_port_, "/metrics");
    const auto journaled = metric("eip2mqtt_history_journaled_total");
    ASSERT_TRUE(journaled.has_value());
    ASSERT_GE(*journaled, 250);
    ASSERT_TRUE(wait_metric("eip2mqtt_history_entries", [&](double v) { return v == *journaled; }))
        << http_get(prometheus_port_, "/metrics");

    gateway_->signal(SIGKILL);
    ASSERT_TRUE(gateway_->wait(5s).has_value());
    options_.wait_online = false;  // the broker is still down
    start_gateway();
    // Its socket is bound: what the counter sends now is received.
    ASSERT_TRUE(gateway_->wait_for_output("listening on UDP", 10s)) << gateway_->output();
    counter_->resume();
    std::this_thread::sleep_for(2s);  // the scenario: the outage goes on after the restart

    const auto last = end_outage_once_live_again();
    EXPECT_TRUE(wait_all_received(last)) << gateway_->output();
    expect_each_value_once(last);
}

TEST_F(StoreAndForwardTest, AReconnectDuringTheReplayResumesWhereItStopped) {
    // 50 a second: 4 s of outage take 8 s to replay, and the broker goes again meanwhile.
    start_gateway_with("    enabled: true\n    replay_rate: 50\n", true);
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 10s));
    stop_broker();
    std::this_thread::sleep_for(4s);  // the scenario: the first outage
    auto from = recorder_->count();
    broker_->start();
    wait_online(from);
    ASSERT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) { return values_on("_history", all).size() >= 50; },
        20s));
    stop_broker();
    std::this_thread::sleep_for(1s);  // the scenario: the second outage
    from = recorder_->count();
    broker_->start();
    wait_online(from);
    const auto last = counter_->pause();
    EXPECT_TRUE(wait_all_received(last, 90s)) << gateway_->output();
    expect_each_value_once(last, 2);
    EXPECT_TRUE(wait_metric("eip2mqtt_history_entries", [](double v) { return v == 0; }))
        << http_get(prometheus_port_, "/metrics") << gateway_->output();
}

TEST_F(StoreAndForwardTest, WithSparkplugTheHistoryIsAlsoHistoricalDdata) {
    // 20 a second: the edge node, on a connection of its own, is born again long before the
    // replay of one second of outage ends. Its DDATA are QoS 0, which the broker drops for a
    // subscriber away: the node has a primary host, whose STATE says online once the test's
    // subscriber is back, and the node is born (and replays) only then.
    start_gateway_with("    enabled: true\n    replay_rate: 20\n", false,
                       "sparkplug:\n  group_id: plant\n  primary_host_id: scada\n");
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":1})", true);
    const std::string ddata = "spBv1.0/plant/DDATA/test-gw/line";
    ASSERT_TRUE(recorder_->wait_for_message(ddata, nullptr, 10s));
    stop_broker();
    std::this_thread::sleep_for(1s);  // the scenario: a short outage
    // The counter stops before the broker returns: what comes as DDATA after it is history.
    const auto last = counter_->pause();
    const auto from = recorder_->count();
    broker_->start();
    wait_online(from);
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":2})", true);
    ASSERT_TRUE(wait_all_received(last)) << gateway_->output();
    const auto history = values_on("_history");
    ASSERT_FALSE(history.empty());
    ASSERT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            return std::any_of(all.begin() + static_cast<std::ptrdiff_t>(from), all.end(),
                               [&](const Received& m) { return m.topic == ddata; });
        },
        10s));

    // Read by Tahu: every metric of those DDATA is historical, each a journaled value of the
    // JSON tree's history, in its order. (The node sends history only while it is born, so it
    // may have missed the replay's first entries.)
    std::vector<std::uint64_t> historical;
    const auto messages = recorder_->messages();
    std::vector<std::string> payloads;  // decoded in one run of Node.js, not one each
    for (const auto* m : deliveries(ddata, messages, from)) payloads.push_back(m->payload);
    for (const auto& payload : tahu_decode_all(payloads)) {
        for (const auto& metric : payload["metrics"]) {
            EXPECT_EQ(metric.value("isHistorical", false), true) << metric.dump();
            historical.push_back(metric["value"].get<std::uint64_t>());
        }
    }
    ASSERT_FALSE(historical.empty());
    EXPECT_TRUE(std::is_sorted(historical.begin(), historical.end()));
    EXPECT_TRUE(std::adjacent_find(historical.begin(), historical.end()) == historical.end());
    const std::set<std::uint64_t> journaled(history.begin(), history.end());
    for (const auto v : historical) EXPECT_TRUE(journaled.contains(v)) << v;
}

TEST_F(StoreAndForwardTest, AtTheBoundTheOldestEntriesAreDroppedAndCounted) {
    // 1 MB holds some thousands of 4-byte counter entries: with 350 tags changing at once an
    // entry is 100 times larger, and a few hundred datagrams fill it.
    auto line = ExchangeYaml::consume("wide", "10.0.0.3", 8);
    line.length(1400).timeout_ms(0);
    for (int i = 0; i < 350; ++i) {
        line.tag("T" + std::to_string(i), std::to_string(i * 4) + ".0", "udint");
    }
    const auto port = free_tcp_port();
    GatewayOptions options;
    options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port) + "\n";
    prometheus_port_ = port;
    start(line.str(), "  store_and_forward:\n    enabled: true\n    max_mb: 1\n",
          std::move(options));
    stop_broker();
    // The bound holds at all times, however slow the machine: the journal's files (database,
    // WAL and reserve) are measured while the datagrams come, not only after.
    double largest = 0;
    for (std::uint32_t n = 1; n <= 1500; ++n) {
        DatagramBuilder datagram("10.0.0.3", 8, 1400);
        datagram.request_id(static_cast<std::uint16_t>(n));
        for (std::uint16_t i = 0; i < 350; ++i) {
            datagram.set(std::to_string(i * 4) + ".0", TagType::udint,
                         std::uint64_t{n * 1000u + i});
        }
        send(datagram.build());
        std::this_thread::sleep_for(2ms);  // pacing: the socket's buffer, not synchronisation
        if (n % 100 == 0) largest = std::max(largest, metric("eip2mqtt_history_bytes").value_or(0));
    }
    ASSERT_TRUE(wait_metric("eip2mqtt_history_dropped_total", [](double v) { return v > 0; }))
        << http_get(prometheus_port_, "/metrics");
    const auto bytes = metric("eip2mqtt_history_bytes");
    ASSERT_TRUE(bytes.has_value());
    EXPECT_LE(*bytes, 1 << 20);
    EXPECT_LE(largest, 1 << 20);
    std::cout << "journal bytes at the end " << static_cast<std::uint64_t>(*bytes) << ", at most "
              << static_cast<std::uint64_t>(largest) << " seen\n";
    // Live data goes on through it all: the gateway accepted every datagram it was sent.
    EXPECT_TRUE(
        wait_metric("eip2mqtt_datagrams_accepted_total", [](double v) { return v >= 1400; }));
}

TEST_F(StoreAndForwardTest, ADamagedJournalIsSetAsideAndTheGatewayStarts) {
    std::filesystem::create_directories(dir_.path() + "/state");
    dir_.write("state/history.sqlite", std::string(8192, 'x'));
    start_gateway_with(kEnabled);
    EXPECT_TRUE(gateway_->wait_for_output("set aside", 5s)) << gateway_->output();
    bool aside = false;
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path() + "/state")) {
        aside |= entry.path().filename().string().rfind("history.sqlite.damaged-", 0) == 0;
    }
    EXPECT_TRUE(aside);
    // The new journal works: an outage is journaled and replayed.
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 10s));
    stop_broker();
    std::this_thread::sleep_for(1s);  // the scenario: a short outage
    const auto from = recorder_->count();
    broker_->start();
    wait_online(from);
    const auto last = counter_->pause();
    EXPECT_TRUE(wait_all_received(last)) << gateway_->output();
    expect_each_value_once(last);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
