// The benchmark's own instruments (bench/README.md) must count exactly, or every ratio of the
// table is wrong: each pair (generator and sink, publisher and counter) is run once, at a
// modest rate, and the counts compared. No figure is asserted: performance is the benchmark's
// job, never a test's.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
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
    Mosquitto broker;
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
