// The gateway owns its state directory: it refuses to start, saying which directory and why,
// when the directory cannot be created or written (a read-only file system, a user without
// the right to write there), and when another gateway holds it (named: pid, gateway id,
// configuration file).

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// A whole configuration with this state_dir: a produced exchange, and a broker nobody
/// listens on (the refusals come before any connection).
std::string configuration(const std::string& id, const std::string& state_dir) {
    return "gateway:\n  id: " + id + "\n  state_dir: " + state_dir +
           "\nmqtt:\n  url: tcp://127.0.0.1:1\n  base_topic: test\neip:\n  bind: 127.0.0.1\n"
           "  port: " +
           std::to_string(free_udp_port()) + "\nexchanges:\n" +
           ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:9")
               .period_ms(1000)
               .tag("VALUE", "0.0", "dint", "writable: true")
               .str();
}

RunResult run(const std::string& config_path, std::vector<std::string> prefix = {}) {
    prefix.insert(prefix.end(), {gateway_binary(), "run", "-c", config_path});
    return run_command(std::move(prefix), 10s);
}

class StateDirTest : public GatewayTest {};

TEST_F(StateDirTest, ASecondGatewayOnTheSameStateDirIsRefusedNamingTheFirst) {
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:9")
              .period_ms(1000)
              .tag("VALUE", "0.0", "dint", "writable: true")
              .str());
    // Another gateway id, another port: only the state directory is shared.
    const auto second =
        dir_.write("second.yaml", configuration("other-gw", dir_.path() + "/state"));
    const auto result = run(second);
    EXPECT_EQ(result.status, 1) << result.output;
    const auto expected = "gateway.state_dir " + dir_.path() +
                          "/state is in use by another eip2mqtt (pid " +
                          std::to_string(gateway_->pid()) + ", gateway.id test-gw, config " +
                          config_path_ + ", started ";
    EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
    // The first one goes on, its state untouched.
    EXPECT_TRUE(gateway_->running());
    const auto from = recorder_->count();
    recorder_->publish(topic("sp/VALUE/set"), "5");
    EXPECT_TRUE(recorder_->wait_for_message(
        topic("sp/VALUE/set/result"), [](const std::string& p) { return p == R"({"ok":true})"; },
        10s, from));
}

TEST_F(StateDirTest, AReadOnlyStateDirIsRefusedAtStart) {
    Tmpfs read_only(64 * 1024, true);
    if (!read_only.mounted()) GTEST_SKIP() << read_only.error();
    const auto config = dir_.write("ro.yaml", configuration("gw", read_only.path()));
    const auto result = run(config);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find("gateway.state_dir " + read_only.path() +
                                 " is not writable: cannot open " + read_only.path() +
                                 "/eip2mqtt.lock (Read-only file system)"),
              std::string::npos)
        << result.output;
}

TEST_F(StateDirTest, AStateDirTheServiceUserMayNotWriteIsRefusedAtStart) {
    // Owned by root, run as nobody: what a unit without StateDirectory= would do.
    const auto state = dir_.path() + "/root-only";
    std::filesystem::create_directories(state);
    const auto config = dir_.write("nobody.yaml", configuration("gw", state));
    ASSERT_EQ(::chmod(dir_.path().c_str(), 0755), 0);
    ASSERT_EQ(::chmod(config.c_str(), 0644), 0);
    const auto result =
        run(config, {"/usr/bin/setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"});
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(
        result.output.find("gateway.state_dir " + state + " is not writable: cannot open " + state +
                           "/eip2mqtt.lock (Permission denied); it must belong to "
                           "the user the gateway runs as"),
        std::string::npos)
        << result.output;
}

TEST_F(StateDirTest, AStateDirThatCannotBeCreatedIsRefusedAtStart) {
    const auto file = dir_.write("plain-file", "x");
    const auto config = dir_.write("bad.yaml", configuration("gw", file + "/state"));
    const auto result = run(config);
    EXPECT_EQ(result.status, 1) << result.output;
    EXPECT_NE(result.output.find("gateway.state_dir " + file + "/state cannot be created: "),
              std::string::npos)
        << result.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
