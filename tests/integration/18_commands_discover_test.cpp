// `eip2mqtt discover` against the real binary answering on UDP 7937 (docs/protocol.md §9):
// the simulator, which describes the exchanges it sends, and the gateway's responder, which
// describes every configured exchange; what --yaml prints passes `check`.

#include <csignal>
#include <regex>
#include <string>

#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// A table row: producer id, exchange id, mode, period, length, destination, port, signature,
// state, the columns separated by spaces.
bool has_row(const std::string& output, const std::string& row) {
    std::string pattern = "\\n *";
    for (std::size_t start = 0; start < row.size();) {
        const auto space = row.find(' ', start);
        const auto word = row.substr(start, space - start);
        pattern += std::regex_replace(word, std::regex(R"([.()])"), R"(\$&)") + " +";
        start = space == std::string::npos ? row.size() : space + 1;
    }
    pattern.resize(pattern.size() - 2);
    return std::regex_search(output, std::regex(pattern + "\\n"));
}

std::string port_text(std::uint16_t port) { return std::to_string(port); }

TEST(CommandsDiscover, DiscoverListsWhatTheSimulatorSendsAndItsYamlPassesCheck) {
    TempDir dir;
    const auto commands_port = free_udp_port();
    const auto data_port = free_udp_port();
    const auto config =
        dir.write("sim.yaml",
                  "mqtt: { url: tcp://127.0.0.1:1 }\n"
                  "eip:\n  bind: 127.0.0.1\n  port: " +
                      port_text(data_port) + "\n  commands: { enabled: true, port: " +
                      port_text(commands_port) + " }\nexchanges:\n" +
                      ExchangeYaml::consume("turbine", "10.0.0.9", 3)
                          .period_ms(50)
                          .tag("SPEED", "0.0", "real")
                          .tag("RUN", "4.0", "bit")
                          .str() +
                      ExchangeYaml::consume("spare", "10.0.0.9", 4)
                          .length(16)
                          .period_ms(250)
                          .key("signature", "\"2.1\"")
                          .str());
    ChildProcess sim({gateway_binary(), "sim", "-c", config, "--duration", "120"});
    ASSERT_TRUE(sim.wait_for_output("answering the command protocol", 20s)) << sim.output();

    const auto node = "127.0.0.1:" + port_text(commands_port);
    const auto table = run_command({gateway_binary(), "discover", node}, 60s);
    EXPECT_EQ(table.status, 0) << table.output;
    EXPECT_TRUE(contains(table.output, node + ": \"eip2mqtt sim ")) << table.output;
    EXPECT_TRUE(contains(table.output, "\", 2 exchanges\n")) << table.output;
    const auto data = port_text(data_port);
    EXPECT_TRUE(has_row(table.output, "10.0.0.9 3 produced 50 5 127.0.0.1 " + data + " 0.0 active"))
        << table.output;
    EXPECT_TRUE(
        has_row(table.output, "10.0.0.9 4 produced 250 16 127.0.0.1 " + data + " 2.1 active"))
        << table.output;

    const auto yaml = run_command({gateway_binary(), "discover", node, "--yaml"}, 60s);
    EXPECT_EQ(yaml.status, 0) << yaml.output;
    const auto checked =
        dir.write("discovered.yaml", "mqtt: { url: tcp://127.0.0.1:1 }\n" + yaml.output);
    const auto check = run_command({gateway_binary(), "check", "-c", checked}, 30s);
    EXPECT_EQ(check.status, 0) << check.output << yaml.output;
    EXPECT_TRUE(contains(check.output,
                         "exchange 10.0.0.9-4: consume, producer 10.0.0.9, "
                         "exchange 4, 16 bytes, period 250 ms"))
        << check.output;
    EXPECT_TRUE(contains(check.output, "signature 2.1")) << check.output;

    sim.signal(SIGTERM);
    EXPECT_EQ(sim.wait(10s), 0);
}

TEST(CommandsDiscover, ANodeThatDoesNotAnswerIsReportedAfterItsAttempts) {
    const auto silent = "127.0.0.1:" + port_text(free_udp_port());
    const auto started = std::chrono::steady_clock::now();
    const auto result = run_command(
        {gateway_binary(), "discover", silent, "--timeout-ms", "100", "--attempts", "2"}, 30s);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_TRUE(contains(result.output, silent + ": no answer after 2 attempts of 100 ms"))
        << result.output;
    // The attempts are bounded: at least their timeouts passed.
    EXPECT_GE(std::chrono::steady_clock::now() - started, 200ms);
}

class DaemonDiscoverTest : public GatewayTest {};

TEST_F(DaemonDiscoverTest, DiscoverListsEveryConfiguredExchangeOfTheGateway) {
    UdpClient capture;
    const auto commands_port = free_udp_port();
    GatewayOptions options;
    options.eip_extra = "  commands: { enabled: true, port: " + port_text(commands_port) + " }\n";
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + port_text(capture.port()))
                  .period_ms(100)
                  .tag("SPEED_SP", "0.0", "real", "writable: true")
                  .str() +
              ExchangeYaml::consume("plant", "10.9.9.9", 1)
                  .length(2)
                  .period_ms(200)
                  .key("source", "127.0.0.9")
                  .tag("PV", "0.0", "int")
                  .str(),
          "", options);
    const auto node = "127.0.0.1:" + port_text(commands_port);
    const auto table = run_command({gateway_binary(), "discover", node}, 60s);
    EXPECT_EQ(table.status, 0) << table.output;
    EXPECT_TRUE(contains(table.output, node + ": \"eip2mqtt ")) << table.output;
    EXPECT_TRUE(contains(table.output, "\", 2 exchanges\n")) << table.output;
    EXPECT_TRUE(has_row(table.output, "10.1.2.3 10 produced 100 4 127.0.0.1 " +
                                          port_text(capture.port()) + " 0.0 active"))
        << table.output;
    // Consumed, never received: idle; described by where its data comes from.
    EXPECT_TRUE(has_row(
        table.output, "10.9.9.9 1 consumed 200 2 127.0.0.9 " + port_text(udp_port_) + " 0.0 idle"))
        << table.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
