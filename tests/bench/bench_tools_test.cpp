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

/// Waits (bounded) for a tool's --ready-file: it is subscribed or bound from then on.
bool wait_ready(const std::string& file, ChildProcess& process) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline && process.running()) {
        if (std::filesystem::exists(file)) return true;
        std::this_thread::sleep_for(10ms);
    }
    return false;
}

TEST(BenchTools, UdpSinkReceivesEveryDatagramTheLoadGeneratorSends) {
    TempDir dir;
    const auto port = std::to_string(free_udp_port());
    const auto ready = dir.path() + "/sink.ready";
    // Ends 3 s after the last datagram: a count, not a rate, is what is checked.
    ChildProcess sink({tool("udp_sink"), "--port", port, "--idle-ms", "3000", "--max-s", "60",
                       "--ready-file", ready});
    ASSERT_TRUE(wait_ready(ready, sink)) << sink.output();
    const auto sent =
        run_command({tool("load_generator"), "--port", port, "--exchanges", "3", "--tags", "20",
                     "--rate", "3000", "--count", "600", "--change", "0.1"},
                    30s);
    ASSERT_EQ(sent.status, 0) << sent.output;
    ASSERT_TRUE(sink.wait(70s).has_value());
    const auto generator = last_json(sent.output);
    const auto received = last_json(sink.output());
    ASSERT_TRUE(generator.is_object() && received.is_object()) << sent.output << sink.output();
    EXPECT_EQ(generator["sent"], 600);
    EXPECT_EQ(generator["errors"], 0);
    EXPECT_EQ(received["received"], 600);
}

TEST(BenchTools, MqttCounterCountsEveryMessageThePahoPublisherPublishes) {
    TempDir dir;
    Mosquitto broker;
    const auto ready = dir.path() + "/counter.ready";
    ChildProcess counter({tool("mqtt_counter"), "--port", std::to_string(broker.port()), "--filter",
                          "p/+/+", "--qos", "1", "--expect", "2000", "--max-s", "60",
                          "--ready-file", ready, "--id", "bench-tools-test"});
    ASSERT_TRUE(wait_ready(ready, counter)) << counter.output();
    const auto published =
        run_command({tool("paho_publisher"), "--url", broker.url(), "--qos", "1", "--topics", "10",
                     "--count", "2000", "--window", "64", "--duration", "30"},
                    60s);
    ASSERT_EQ(published.status, 0) << published.output;
    ASSERT_TRUE(counter.wait(70s).has_value());
    const auto publisher = last_json(published.output);
    const auto counted = last_json(counter.output());
    ASSERT_TRUE(publisher.is_object() && counted.is_object())
        << published.output << counter.output();
    EXPECT_EQ(publisher["published"], 2000);
    EXPECT_EQ(publisher["completed"], 2000);
    EXPECT_EQ(publisher["failed"], 0);
    EXPECT_EQ(counted["messages"], 2000);
}

TEST(BenchTools, YamlParseReadsTheWholeFile) {
    const std::string example = std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml";
    const auto parsed = run_command({tool("yaml_parse"), "--file", example, "--repeat", "2"}, 30s);
    ASSERT_EQ(parsed.status, 0) << parsed.output;
    const auto result = last_json(parsed.output);
    ASSERT_TRUE(result.is_object()) << parsed.output;
    EXPECT_EQ(result["bytes"], std::filesystem::file_size(example));
    EXPECT_EQ(result["repeat"], 2);
}

}  // namespace
}  // namespace eip2mqtt::test
