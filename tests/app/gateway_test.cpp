// The composition root built from fake modules around a real (empty) exchanges module on
// loopback: start in order, ticks in order, stop in reverse, a failing start unwinds, a reload
// applied to every module or to none, and the metrics gathered from each.

#include "eip2mqtt/app/gateway.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::app {
namespace {

using namespace std::chrono_literals;

/// What the modules were asked, in order, from the loop's thread and the test's.
class Journal {
public:
    void add(std::string event) {
        {
            std::lock_guard lock(mutex_);
            events_.push_back(std::move(event));
        }
        changed_.notify_all();
    }
    /// True once `event` was added, within 30 s.
    bool wait_for(const std::string& event) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, 30s, [&] {
            return std::find(events_.begin(), events_.end(), event) != events_.end();
        });
    }
    /// The events that start with one of `prefixes`, in order.
    std::vector<std::string> only(std::initializer_list<std::string_view> prefixes) {
        std::lock_guard lock(mutex_);
        std::vector<std::string> out;
        for (const auto& event : events_) {
            for (auto prefix : prefixes) {
                if (event.starts_with(prefix)) out.push_back(event);
            }
        }
        return out;
    }

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<std::string> events_;
};

struct FakeBehaviour {
    bool fail_start = false;
    bool refuse = false;
};

class FakeModule final : public Module {
public:
    FakeModule(std::string name, Journal& journal, FakeBehaviour behaviour = {})
        : name_(std::move(name)), journal_(journal), behaviour_(behaviour) {}

    void start(core::MonoTime) override {
        if (behaviour_.fail_start) throw std::runtime_error(name_ + " cannot start");
        journal_.add("start " + name_);
    }
    void tick(const TickTimes&) override {
        if (ticks_ < 2) journal_.add("tick " + name_ + " " + std::to_string(++ticks_));
    }
    void stop() override { journal_.add("stop " + name_); }
    bool prepare(const core::config::Config& next) override {
        journal_.add("prepare " + name_ + " " + next.gateway.log_level);
        return !behaviour_.refuse;
    }
    void apply(const core::config::Config& next) override {
        journal_.add("apply " + name_ + " " + next.gateway.log_level);
    }
    void applied() override { journal_.add("applied " + name_); }
    void add_metrics(MetricsSources& sources) override { sources.commands = &commands_; }

    core::command::CommandCounters commands_;

private:
    std::string name_;
    Journal& journal_;
    FakeBehaviour behaviour_;
    int ticks_ = 0;
};

constexpr auto exchange_yaml =
    "exchanges:\n  - name: a\n    direction: consume\n    producer_id: 10.0.0.1\n"
    "    exchange_id: 1\n    length: 4\n    tags:\n      - { name: T, address: \"0.0\", type: "
    "dint }\n";

class GatewayTest : public ::testing::Test {
protected:
    GatewayTest() : dir_(std::filesystem::temp_directory_path() / unique_name()) {
        std::filesystem::create_directories(dir_);
        write_config("info");
    }
    ~GatewayTest() override { std::filesystem::remove_all(dir_); }

    static std::string unique_name() {
        return "eip2mqtt-gateway-test-" + std::to_string(::getpid()) + "-" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
    }
    std::string file() const { return (dir_ / "gateway.yaml").string(); }
    void write_config(const std::string& level) {
        std::ofstream(file()) << "gateway:\n  id: gw\n  state_dir: " << (dir_ / "state").string()
                              << "\n  log_level: " << level
                              << "\nmqtt:\n  url: tcp://127.0.0.1:1\neip:\n  bind: 127.0.0.1\n"
                              << "  port: 0\n"
                              << exchange_yaml;
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

    std::filesystem::path dir_;
    Journal journal_;
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
void reload_then_stop(Gateway& gateway, Journal& journal, const std::string& last) {
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

}  // namespace
}  // namespace eip2mqtt::app
