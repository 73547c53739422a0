// The benchmark's own instruments (bench/README.md) must count exactly, or every ratio of the
// table is wrong: each pair (generator and sink, publisher and counter) is run once, at a
// modest rate, and the counts compared. No figure is asserted: performance is the benchmark's
// job, never a test's.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

std::string tool(const std::string& name) { return std::string(EIP2MQTT_BENCH_DIR) + "/" + name; }

/// The last JSON line a tool printed (each prints one result line).
nlohmann::json last_json(const std::string& output) {
    std::istringstream lines(output);
    std::string line;
    std::string last;
    while (std::getline(lines, line)) {
        if (!line.empty() && line.front() == '{') last = line;
    }
    return nlohmann::json::parse(last, nullptr, false);
}

/// What a sending tool and a receiving tool each printed.
struct PairResults {
    nlohmann::json sender;
    nlohmann::json receiver;
};

/// Starts `receiver_argv` (plus `--ready-file`), waits (bounded) until it is bound or
/// subscribed, runs `sender_argv` to completion, then waits for the receiver to end by itself.
/// Fails the test, returning nulls, when a step fails.
PairResults run_pair(std::vector<std::string> receiver_argv,
                     const std::vector<std::string>& sender_argv) {
    TempDir dir;
    const auto ready = dir.path() + "/receiver.ready";
    receiver_argv.insert(receiver_argv.end(), {"--ready-file", ready});
    ChildProcess receiver(receiver_argv);
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!std::filesystem::exists(ready) && receiver.running() &&
           std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(10ms);
    }
    if (!std::filesystem::exists(ready)) {
        ADD_FAILURE() << "the receiver never got ready: " << receiver.output();
        return {};
    }
    const auto sent = run_command(sender_argv, 60s);
    const bool receiver_ended = receiver.wait(70s).has_value();
    EXPECT_EQ(sent.status, 0) << sent.output;
    EXPECT_TRUE(receiver_ended) << receiver.output();
    PairResults results{last_json(sent.output), last_json(receiver.output())};
    EXPECT_TRUE(results.sender.is_object()) << sent.output;
    EXPECT_TRUE(results.receiver.is_object()) << receiver.output();
    return results;
}

TEST(BenchTools, UdpSinkReceivesEveryDatagramTheLoadGeneratorSends) {
    const auto port = std::to_string(free_udp_port());
    // The sink ends 3 s after the last datagram: a count, not a rate, is what is checked.
    const auto [generator, sink] =
        run_pair({tool("udp_sink"), "--port", port, "--idle-ms", "3000", "--max-s", "60"},
                 {tool("load_generator"), "--port", port, "--exchanges", "3", "--tags", "20",
                  "--rate", "3000", "--count", "600", "--change", "0.1"});
    EXPECT_EQ(generator.value("sent", -1), 600);
    EXPECT_EQ(generator.value("errors", -1), 0);
    EXPECT_EQ(sink.value("received", -1), 600);
}

TEST(BenchTools, MqttCounterCountsEveryMessageThePahoPublisherPublishes) {
    // Mosquitto drops what a QoS 1 subscriber has not taken beyond max_queued_messages (1000 by
    // default): on a busy machine the counter fell that far behind and got 1905 of 2000. Here
    // the broker must keep all of them: what is tested is the counter, not the broker's limit.
    MosquittoOptions options;
    options.extra_config = "max_queued_messages 0\n";
    Mosquitto broker(options);
    const auto [publisher, counter] = run_pair(
        {tool("mqtt_counter"), "--port", std::to_string(broker.port()), "--filter", "p/+/+",
         "--qos", "1", "--expect", "2000", "--max-s", "60", "--id", "bench-tools-test"},
        {tool("paho_publisher"), "--url", broker.url(), "--qos", "1", "--topics", "10", "--count",
         "2000", "--window", "64", "--duration", "30"});
    EXPECT_EQ(publisher.value("published", -1), 2000);
    EXPECT_EQ(publisher.value("completed", -1), 2000);
    EXPECT_EQ(publisher.value("failed", -1), 0);
    EXPECT_EQ(counter.value("messages", -1), 2000);
}

/// `mosquitto_pub` of one message at QoS 1: acknowledged by the broker when it returns, so
/// messages published one after the other arrive in that order.
void publish(const Mosquitto& broker, const std::string& topic, const std::string& payload) {
    const auto done =
        run_command({"/usr/bin/mosquitto_pub", "-h", "127.0.0.1", "-p",
                     std::to_string(broker.port()), "-q", "1", "-t", topic, "-m", payload},
                    10s);
    ASSERT_EQ(done.status, 0) << done.output;
}

/// CLOCK_REALTIME in ns, `ago` before now: a stamp the counter turns into a latency.
std::string stamp(std::chrono::seconds ago) {
    const auto now = std::chrono::system_clock::now() - ago;
    return std::to_string(
        std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count());
}

/// Starts mqtt_counter on `broker` with `options`, once subscribed.
std::unique_ptr<ChildProcess> start_counter(const Mosquitto& broker, const TempDir& dir,
                                            std::vector<std::string> options) {
    const auto ready = dir.path() + "/counter.ready";
    std::vector<std::string> argv = {tool("mqtt_counter"),
                                     "--port",
                                     std::to_string(broker.port()),
                                     "--filter",
                                     "p/+/+",
                                     "--qos",
                                     "1",
                                     "--max-s",
                                     "60",
                                     "--ready-file",
                                     ready};
    argv.insert(argv.end(), options.begin(), options.end());
    auto counter = std::make_unique<ChildProcess>(argv);
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!std::filesystem::exists(ready) && counter->running() &&
           std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(10ms);
    }
    EXPECT_TRUE(std::filesystem::exists(ready)) << counter->output();
    return counter;
}

TEST(BenchTools, MqttCounterTakesLatencyFromTheStampTagAndChecksWhereEachTopicEnded) {
    TempDir dir;
    Mosquitto broker;
    auto counter = start_counter(broker, dir, {"--expect", "5", "--expect-last", "7"});
    // Stamped 2 s in the past: each latency is at least 2 s, in microseconds.
    publish(broker, "p/e1/ts", R"({"value":)" + stamp(2s) + R"(,"quality":"good"})");
    publish(broker, "p/e1/ts", R"({"value":)" + stamp(2s) + R"(,"quality":"good"})");
    publish(broker, "p/e1/t1", R"({"value":5})");
    publish(broker, "p/e1/t1", R"({"value":7})");
    publish(broker, "p/e1/_status", R"({"state":"ok"})");  // not a tag: not counted
    publish(broker, "p/e1/t2", R"({"value":7})");
    ASSERT_TRUE(counter->wait(70s).has_value());
    const auto counted = last_json(counter->output());
    ASSERT_TRUE(counted.is_object()) << counter->output();
    EXPECT_EQ(counted.value("messages", -1), 5);
    EXPECT_EQ(counted.value("latency_n", -1), 2);
    EXPECT_GE(counted.value("p50_us", 0.0), 2e6);
    EXPECT_LT(counted.value("max_us", 1e12), 2e6 + 60e6);  // not ns, not an absolute time
    EXPECT_EQ(counted.value("last_ok", -1), 2);            // t1 and t2 ended on 7
    EXPECT_EQ(counted.value("last_bad", -1), 1);           // ts did not
}

TEST(BenchTools, MqttCounterCountsTheTagUpdatesOfBatchMessages) {
    TempDir dir;
    Mosquitto broker;
    auto counter = start_counter(broker, dir, {"--batch", "--expect", "2"});
    publish(broker, "p/e1/t1", R"({"value":1})");  // per-tag: not counted in batch mode
    for (int i = 0; i < 2; ++i) {
        publish(broker, "p/e1/_values",
                R"({"timestamp":1,"quality":"good","values":{"ts":)" + stamp(2s) +
                    R"(,"t1":4,"t2":-5}})");
    }
    ASSERT_TRUE(counter->wait(70s).has_value());
    const auto counted = last_json(counter->output());
    ASSERT_TRUE(counted.is_object()) << counter->output();
    EXPECT_EQ(counted.value("messages", -1), 2);
    EXPECT_EQ(counted.value("updates", -1), 6);
    EXPECT_EQ(counted.value("latency_n", -1), 2);
    EXPECT_GE(counted.value("p50_us", 0.0), 2e6);
}

const std::string node_red_dir = std::string(EIP2MQTT_SOURCE_DIR) + "/bench/peers/node-red";

/// The benchmark's Node-RED peer (bench/peers/node-red, installed by tools/install-deps.sh)
/// running its flow: datagrams on `udp_port` to `{n}/e{exchange}/{tag}` on `broker`, at QoS 1.
/// Returns once a probe datagram (exchange 0) it decoded reached the broker.
std::unique_ptr<ChildProcess> start_node_red(const Mosquitto& broker, const TempDir& dir,
                                             std::uint16_t udp_port) {
    const auto node_red = node_red_dir + "/node_modules/.bin/node-red";
    EXPECT_TRUE(std::filesystem::exists(node_red)) << node_red << ": run tools/install-deps.sh";
    auto peer = std::make_unique<ChildProcess>(
        std::vector<std::string>{node_red, "--settings", node_red_dir + "/settings.js", "--userDir",
                                 dir.path(), node_red_dir + "/flow.json"},
        std::map<std::string, std::string>{
            {"EIP2MQTT_PEER_UDP_PORT", std::to_string(udp_port)},
            {"EIP2MQTT_PEER_BROKER_PORT", std::to_string(broker.port())},
            {"EIP2MQTT_PEER_QOS", "1"},
            {"EIP2MQTT_PEER_BASE", "n"},
            {"EIP2MQTT_PEER_UI_PORT", std::to_string(free_tcp_port())}});
    ChildProcess ready({"/usr/bin/mosquitto_sub", "-h", "127.0.0.1", "-p",
                        std::to_string(broker.port()), "-C", "1", "-W", "90", "-t",
                        "n/_peer/node-red/ready"});
    while (ready.running() && peer->running()) {
        run_command({tool("load_generator"), "--port", std::to_string(udp_port), "--exchanges", "1",
                     "--first-exchange", "0", "--tags", "3", "--rate", "100", "--count", "1"},
                    10s);
        std::this_thread::sleep_for(100ms);
    }
    EXPECT_EQ(ready.wait(5s), std::optional<int>(0)) << peer->output();
    return peer;
}

TEST(BenchTools, NodeRedPeerPublishesEveryTagOfEachDatagramOnTheGatewaysTopicsAndPayloads) {
    TempDir dir;
    Mosquitto broker;
    const auto udp_port = free_udp_port();
    const auto peer = start_node_red(broker, dir, udp_port);
    ASSERT_TRUE(peer->running()) << peer->output();
    const auto port = std::to_string(udp_port);
    // 20 datagrams of 1 exchange x (ts lint + 10 dints), every tag changing, then one setting
    // every tag to 2000000007: 11 messages a datagram, each topic ending on that value.
    const auto [generator, counter] = run_pair(
        {tool("mqtt_counter"), "--port", std::to_string(broker.port()), "--filter", "n/+/+",
         "--qos", "1", "--expect-last", "2000000007", "--expect-topics", "11", "--max-s", "60",
         "--id", "bench-tools-node-red"},
        {tool("load_generator"), "--port", port, "--exchanges", "1", "--tags", "11", "--rate",
         "200", "--count", "20", "--change", "1", "--final-value", "2000000007"});
    EXPECT_EQ(generator.value("sent", -1), 20);
    EXPECT_EQ(counter.value("messages", -1), 21 * 11);
    EXPECT_EQ(counter.value("last_ok", -1), 11);
    EXPECT_EQ(counter.value("last_bad", -1), 0);

    // The gateway's payload on the gateway's topics: eleven messages in a row (a datagram's,
    // or the end of one and the start of the next) name each tag once.
    ChildProcess sub({"/usr/bin/mosquitto_sub", "-h", "127.0.0.1", "-p",
                      std::to_string(broker.port()), "-v", "-C", "11", "-W", "60", "-t", "n/e7/#"});
    while (sub.running()) {
        run_command({tool("load_generator"), "--port", port, "--exchanges", "1", "--first-exchange",
                     "7", "--tags", "11", "--rate", "100", "--count", "1", "--change", "1"},
                    10s);
        std::this_thread::sleep_for(100ms);
    }
    ASSERT_EQ(sub.wait(5s), std::optional<int>(0)) << sub.output();
    std::istringstream lines(sub.output());
    std::set<std::string> topics;
    for (std::string topic, payload; lines >> topic && std::getline(lines >> std::ws, payload);) {
        topics.insert(topic);
        const auto json = nlohmann::json::parse(payload, nullptr, false);
        ASSERT_TRUE(json.is_object()) << payload;
        EXPECT_TRUE(json["value"].is_number_integer()) << payload;
        EXPECT_TRUE(json["timestamp"].is_number_integer()) << payload;
        EXPECT_EQ(json["quality"], "good") << payload;
        EXPECT_EQ(json.size(), 3u) << payload;
    }
    std::set<std::string> tags = {"n/e7/ts"};
    for (int k = 1; k <= 10; ++k) tags.insert("n/e7/t" + std::to_string(k));
    EXPECT_EQ(topics, tags) << sub.output();
}

TEST(BenchTools, YamlParseReadsTheWholeFile) {
    const std::string example = std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml";
    const auto parsed = run_command({tool("yaml_parse"), "--file", example, "--repeat", "2"}, 30s);
    ASSERT_EQ(parsed.status, 0) << parsed.output;
    const auto result = last_json(parsed.output);
    ASSERT_TRUE(result.is_object()) << parsed.output;
    EXPECT_EQ(result.value("bytes", std::uintmax_t{0}), std::filesystem::file_size(example));
    EXPECT_EQ(result.value("repeat", -1), 2);
}

}  // namespace
}  // namespace eip2mqtt::test
