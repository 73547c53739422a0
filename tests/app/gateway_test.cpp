// The composition root built from fake modules around a real (empty) exchanges module on
// loopback: start in order, ticks in order, stop in reverse, a failing start unwinds, a reload
// applied to every module or to none, and the metrics gathered from each.

#include "eip2mqtt/app/gateway.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "tests/support/fakes/fake_module.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

using test::FakeBehaviour;
using test::FakeModule;
using test::ModuleJournal;

constexpr auto exchange_yaml =
    "exchanges:\n  - name: a\n    direction: consume\n    producer_id: 10.0.0.1\n"
    "    exchange_id: 1\n    length: 4\n    tags:\n      - { name: T, address: \"0.0\", type: "
    "dint }\n";

class GatewayTest : public ::testing::Test {
protected:
    GatewayTest() { write_config("info"); }

    std::string file() const { return dir_.path() + "/gateway.yaml"; }
    void write_config(const std::string& level) {
        dir_.write("gateway.yaml", "gateway:\n  id: gw\n  state_dir: " + dir_.path() +
                                       "/state\n  log_level: " + level +
                                       "\nmqtt:\n  url: tcp://127.0.0.1:1\neip:\n  bind: "
                                       "127.0.0.1\n  port: 0\n" +
                                       exchange_yaml);
    }

    /// A gateway of the file's configuration made of fake modules A and B around the real,
    /// empty exchanges module.
    std::unique_ptr<Gateway> make(FakeBehaviour a = {}, FakeBehaviour b = {}) {
        auto loaded = adapters::yaml::load_config(file());
        EXPECT_TRUE(loaded);
        return std::make_unique<Gateway>(
            std::move(loaded).value(), adapters::clock::system_clock(),
            [&, a, b](Gateway&, boost::asio::io_context& loop, ExchangesModule*& exchanges) {
                std::vector<std::unique_ptr<Module>> modules;
                modules.push_back(std::make_unique<FakeModule>("A", journal_, a));
                auto south = std::make_unique<ExchangesModule>(
                    config_for_exchanges(), loop.get_executor(), adapters::clock::system_clock(),
                    ExchangesOptions{});
                exchanges = south.get();
                modules.push_back(std::move(south));
                modules.push_back(std::make_unique<FakeModule>("B", journal_, b));
                return modules;
            });
    }
    core::config::Config config_for_exchanges() {
        auto loaded = adapters::yaml::load_config(file());
        return std::move(loaded).value();
    }

    test::TempDir dir_;
    ModuleJournal journal_;
};

TEST_F(GatewayTest, StartsAndTicksInOrderAndStopsInReverse) {
    auto gateway = make();
    std::thread runner([&] { EXPECT_EQ(gateway->run(), 0); });
    ASSERT_TRUE(journal_.wait_for("tick B 2"));
    gateway->request_stop();
    runner.join();
    EXPECT_EQ(journal_.only({"start", "stop"}),
              (std::vector<std::string>{"start A", "start B", "stop B", "stop A"}));
    EXPECT_EQ(journal_.only({"tick"}),
              (std::vector<std::string>{"tick A 1", "tick B 1", "tick A 2", "tick B 2"}));
}

TEST_F(GatewayTest, AFailingStartStopsWhatStartedBeforeAndThrows) {
    auto gateway = make({}, {.fail_start = true});
    EXPECT_THROW(gateway->run(), std::runtime_error);
    EXPECT_EQ(journal_.only({"start", "stop", "tick"}),
              (std::vector<std::string>{"start A", "stop A"}));
}

TEST_F(GatewayTest, TheMetricsGatherEveryModulesCounters) {
    auto gateway = make();
    const auto sources = gateway->metrics_sources();
    EXPECT_NE(sources.commands, nullptr);
    EXPECT_EQ(sources.datagrams.datagrams, 0u);
}

/// Runs `gateway`, reloads the file once it started, and stops once `last` was seen.
void reload_then_stop(Gateway& gateway, ModuleJournal& journal, const std::string& last) {
    std::thread runner([&] { EXPECT_EQ(gateway.run(), 0); });
    ASSERT_TRUE(journal.wait_for("tick B 1"));
    ::kill(::getpid(), SIGHUP);  // the gateway's signal set takes it on its loop
    EXPECT_TRUE(journal.wait_for(last));
    // The reload's handler runs whole on the loop: once stopped, it is over.
    gateway.request_stop();
    runner.join();
}

TEST_F(GatewayTest, AReloadIsAppliedToEveryModuleInOrder) {
    auto gateway = make();
    write_config("debug");
    reload_then_stop(*gateway, journal_, "applied B");
    EXPECT_EQ(journal_.only({"prepare", "apply", "applied"}),
              (std::vector<std::string>{"prepare A debug", "prepare B debug", "apply A debug",
                                        "apply B debug", "applied A", "applied B"}));
}

TEST_F(GatewayTest, AModuleThatCannotTakeAReloadRefusesItWhole) {
    auto gateway = make({}, {.refuse = true});
    write_config("debug");
    reload_then_stop(*gateway, journal_, "prepare B debug");
    EXPECT_EQ(journal_.only({"prepare", "apply", "applied"}),
              (std::vector<std::string>{"prepare A debug", "prepare B debug"}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
