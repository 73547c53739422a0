// From the wire to a configuration: `sniff --yaml` ends with the YAML of every
// exchange it saw that the configuration lacks; `check` accepts it as it is, and a gateway run
// on it publishes each exchange's `_status` before any tag is known.

#include <gtest/gtest.h>

#include <csignal>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string turbine_exchange = ExchangeYaml::consume("turbine", "10.0.0.9", 3)
                                         .key("signature", "\"1.0\"")
                                         .period_ms(20)
                                         .tag("SPEED", "0.0", "real")
                                         .tag("RUN", "4.0", "bit")
                                         .tag("COUNT", "6.0", "word")
                                         .str();

const std::string aux_exchange = ExchangeYaml::consume("aux", "10.0.0.9", 4)
                                     .length(12)
                                     .period_ms(30)
                                     .tag("LEVEL", "0.0", "int")
                                     .str();

/// A configuration of `exchanges` on UDP `port` whose broker is never reached: for sim, sniff
/// and check, which do not connect.
std::string offline_config(std::uint16_t port, const std::string& exchanges) {
    return "mqtt:\n"
           "  url: tcp://127.0.0.1:1\n"
           "  base_topic: test\n"
           "eip:\n"
           "  bind: 127.0.0.1\n"
           "  port: " +
           std::to_string(port) + "\nexchanges:\n" + exchanges;
}

/// Runs `sniff --yaml` on `port` until it has seen `count` datagrams (`config`: its -c, or
/// none); returns its output.
std::string sniff_yaml(std::uint16_t port, int count, const std::string& config = "") {
    std::vector<std::string> argv{
        gateway_binary(), "sniff",  "--port",  std::to_string(port), "--bind",
        "127.0.0.1",      "--yaml", "--count", std::to_string(count)};
    if (!config.empty()) argv.insert(argv.end(), {"-c", config});
    ChildProcess sniff(argv);
    EXPECT_EQ(sniff.wait(30s), 0) << sniff.output();
    return sniff.output();
}

/// The skeleton at the end of sniff's output: from its `exchanges:` line on, or empty.
std::string skeleton_of(const std::string& output) {
    const auto start = output.find("\nexchanges:\n");
    return start == std::string::npos ? std::string() : output.substr(start + 1);
}

/// `skeleton` without its `exchanges:` line: the list, as GatewayTest::start takes it.
std::string items_of(const std::string& skeleton) {
    return skeleton.substr(std::string("exchanges:\n").size());
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

class SniffYamlTest : public GatewayTest {};

TEST_F(SniffYamlTest, TheSkeletonPassesCheckAndTheGatewayPublishesItsStatus) {
    const auto port = free_udp_port();
    const auto sim_config =
        dir_.write("sim.yaml", offline_config(port, turbine_exchange + aux_exchange));
    // The simulator plays the undocumented PLC throughout: for sniff, then for the gateway.
    ChildProcess sim({gateway_binary(), "sim", "-c", sim_config, "--duration", "120"});
    ASSERT_TRUE(sim.wait_for_output("simulating exchange aux")) << sim.output();

    const auto output = sniff_yaml(port, 40);
    const auto skeleton = skeleton_of(output);
    ASSERT_FALSE(skeleton.empty()) << output;
    for (const auto* part :
         {"  - name: \"10.0.0.9-3\"\n    direction: consume\n    producer_id: 10.0.0.9\n"
          "    exchange_id: 3\n    length: 8  # data bytes\n    signature: \"1.0\"\n",
          "  - name: \"10.0.0.9-4\"\n    direction: consume\n    producer_id: 10.0.0.9\n"
          "    exchange_id: 4\n    length: 12  # data bytes\n    # signature: none",
          "    topic: \"10-0-0-9/3\"", "    # destination: unicast to 127.0.0.1\n",
          "    # clock: synced (the producer's time is ",
          " ms: time between receive times per request-id step, over "}) {
        EXPECT_TRUE(contains(skeleton, part)) << part << "\nin:\n" << skeleton;
    }
    EXPECT_TRUE(contains(output, "# sniff --yaml: 2 exchanges seen on the wire")) << output;

    // check takes it as it is.
    const auto checked = dir_.write("skeleton.yaml", offline_config(port, items_of(skeleton)));
    const auto check = run_command({gateway_binary(), "check", "-c", checked}, 30s);
    EXPECT_EQ(check.status, 0) << check.output;
    EXPECT_TRUE(contains(check.output, "no tags yet: only test/10-0-0-9/3/_status is published"))
        << check.output;

    // A gateway on it, fed by the same simulator: each exchange's _status says ok, and its
    // accepted count grows.
    udp_port_ = port;
    start(items_of(skeleton));
    for (const auto* status : {"10-0-0-9/3/_status", "10-0-0-9/4/_status"}) {
        const auto ok = expect_field(topic(status), "state", "\"ok\"");
        const auto first = nlohmann::json::parse(ok.payload)["accepted"].get<std::uint64_t>();
        const auto later = recorder_->wait_for_message(
            topic(status),
            [&](const std::string& payload) {
                const auto json = nlohmann::json::parse(payload);
                return json["state"] == "ok" && json["accepted"].get<std::uint64_t>() > first;
            },
            15s, recorder_->count());
        EXPECT_TRUE(later.has_value()) << status;
    }
    // No tag topics: only the exchanges' _status and _meta under their topics.
    for (const auto& message : recorder_->messages()) {
        if (message.topic.rfind(topic("10-0-0-9/"), 0) == 0) {
            EXPECT_TRUE(message.topic.ends_with("/_status") || message.topic.ends_with("/_meta"))
                << message.topic;
        }
    }
    sim.signal(SIGTERM);
    EXPECT_EQ(sim.wait(10s), 0) << sim.output();
}

TEST(SniffYaml, ConfiguredExchangesGetNoSkeleton) {
    TempDir dir;
    const auto port = free_udp_port();
    const auto both = dir.write("both.yaml", offline_config(port, turbine_exchange + aux_exchange));
    ChildProcess sim({gateway_binary(), "sim", "-c", both, "--duration", "120"});
    ASSERT_TRUE(sim.wait_for_output("simulating exchange aux")) << sim.output();

    // The configuration has turbine (10.0.0.9/3): only aux (10.0.0.9/4) gets a skeleton.
    const auto one = dir.write("turbine.yaml", offline_config(port, turbine_exchange));
    const auto output = sniff_yaml(port, 20, one);
    EXPECT_TRUE(contains(output, "[turbine]")) << output;  // seen, and decoded
    const auto skeleton = skeleton_of(output);
    EXPECT_TRUE(contains(output, "# sniff --yaml: 1 exchange seen on the wire")) << output;
    EXPECT_TRUE(contains(skeleton, "    exchange_id: 4\n")) << skeleton;
    EXPECT_FALSE(contains(skeleton, "exchange_id: 3")) << skeleton;

    // With both configured: nothing to add.
    const auto all = sniff_yaml(port, 20, both);
    EXPECT_TRUE(contains(all,
                         "# sniff --yaml: no exchange seen on the wire that the "
                         "configuration lacks\n"))
        << all;
    EXPECT_TRUE(skeleton_of(all).empty()) << all;

    sim.signal(SIGTERM);
    EXPECT_EQ(sim.wait(10s), 0) << sim.output();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
