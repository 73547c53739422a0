// The exchanges module on loopback (eip.port 0): a datagram sent to its port reaches a consumer
// through the receiver and Exchanges::route, with the loop running or read by a tick alone; a
// reload's multicast groups are joined in prepare() or refused whole, the running ones kept;
// apply_plans() returns its line and counts the writes it cancelled.

#include "eip2mqtt/app/exchanges/exchanges_module.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <string>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/reload/reload_sequence.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/igmp.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr auto consumed_yaml =
    "  - { name: a, direction: consume, producer_id: 10.0.0.1, exchange_id: 1, length: 4,\n"
    "      tags: [ { name: T, address: \"0.0\", type: dint } ] }\n";
constexpr auto produced_yaml =
    "  - { name: out, direction: produce, producer_id: 10.0.0.1, exchange_id: 2, length: 4,\n"
    "      destination: 127.0.0.1, period_ms: 60000,\n"
    "      tags: [ { name: V, address: \"0.0\", type: dint, writable: true } ] }\n";

class ExchangesModuleTest : public ::testing::Test {
protected:
    ExchangesModuleTest()
        : dir_(fs::temp_directory_path() /
               ("eip2mqtt_exchanges_module_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()))) {
        fs::remove_all(dir_);
        // The gateway makes it (StateDirLock) before any module.
        fs::create_directories(dir_ / "state");
    }
    ~ExchangesModuleTest() override {
        module_.reset();
        fs::remove_all(dir_);
    }

    /// A configuration of `exchanges`, its multicast groups `multicast` (YAML flow list).
    core::config::Config config(const std::string& exchanges, const std::string& multicast = "[]") {
        auto loaded = adapters::yaml::load_config_text(
            "gateway:\n  id: gw\n  state_dir: " + (dir_ / "state").string() +
                "\nmqtt:\n  url: tcp://127.0.0.1:1\neip:\n  bind: 127.0.0.1\n  port: 0\n"
                "  multicast: " +
                multicast + "\nexchanges:\n" + exchanges,
            (dir_ / "gateway.yaml").string());
        EXPECT_TRUE(loaded);
        return std::move(loaded).value();
    }
    void make(core::config::Config config) {
        module_ = std::make_unique<ExchangesModule>(config, loop_.get_executor(), clock_,
                                                    ExchangesOptions{});
        module_->north().add(northbound_);
        module_->apply_plans(reload::take_plans(config));
    }
    TickTimes tick_times() const { return {clock_.monotonic(), clock_.wall(), false}; }
    std::uint64_t datagrams() const { return module_->exchanges().datagram_counters().datagrams; }

    fs::path dir_;
    boost::asio::io_context loop_;
    test::FakeClock clock_;
    test::RecordingNorthbound northbound_;
    std::unique_ptr<ExchangesModule> module_;
    test::UdpClient plc_;
    const std::vector<std::byte> datagram_ =
        test::DatagramBuilder("10.0.0.1", 1, 4).request_id(1).build();
};

TEST_F(ExchangesModuleTest, ADatagramSentToItsPortReachesTheConsumer) {
    make(config(consumed_yaml));
    ASSERT_NE(module_->local_port(), 0);
    module_->start(clock_.monotonic());
    plc_.send_to(module_->local_port(), datagram_);
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (northbound_.batches.empty() && std::chrono::steady_clock::now() < deadline) {
        loop_.run_one_for(100ms);
    }
    ASSERT_EQ(northbound_.batches.size(), 1u);
    EXPECT_EQ(northbound_.batches[0].exchange, "a");
    EXPECT_EQ(module_->exchanges().datagram_counters().accepted, 1u);
    module_->stop();
}

TEST_F(ExchangesModuleTest, ATickReadsWhatIsPendingWithoutTheLoopRunning) {
    make(config(consumed_yaml));
    module_->start(clock_.monotonic());
    module_->tick(tick_times());
    EXPECT_EQ(datagrams(), 0u);
    plc_.send_to(module_->local_port(), datagram_);
    // Loopback delivers as it is sent; the bound only keeps a slow machine from failing.
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (datagrams() == 0 && std::chrono::steady_clock::now() < deadline) {
        module_->tick(tick_times());
    }
    EXPECT_EQ(datagrams(), 1u);
    EXPECT_EQ(module_->exchanges().datagram_counters().accepted, 1u);
    EXPECT_EQ(northbound_.batches.size(), 1u);
    module_->stop();
}

TEST_F(ExchangesModuleTest, PrepareRefusesAGroupThatCannotBeJoinedAndKeepsTheOld) {
    const auto first = test::test_multicast_group(21);
    const auto second = test::test_multicast_group(22);
    const auto list = [](const std::string& group, const std::string& interface) {
        return "{ group: " + group + ", interface: " + interface + " }";
    };
    make(config(consumed_yaml, "[ " + list(first, "lo") + " ]"));
    ASSERT_TRUE(test::igmp_joined("lo", first));

    EXPECT_FALSE(module_->prepare(config(
        consumed_yaml, "[ " + list(second, "lo") + ", " + list(first, "no-such-if0") + " ]")));
    EXPECT_TRUE(test::igmp_joined("lo", first));
    EXPECT_FALSE(test::igmp_joined("lo", second));
    // What it holds is what it had: the running groups ask for nothing.
    EXPECT_TRUE(module_->prepare(config(consumed_yaml, "[ " + list(first, "lo") + " ]")));
    EXPECT_TRUE(test::igmp_joined("lo", first));

    EXPECT_TRUE(module_->prepare(config(consumed_yaml, "[ " + list(second, "lo") + " ]")));
    EXPECT_FALSE(test::igmp_joined("lo", first));
    EXPECT_TRUE(test::igmp_joined("lo", second));
}

TEST_F(ExchangesModuleTest, ApplyPlansReturnsItsLineAndCountsTheWritesItCancelled) {
    make(config(produced_yaml));
    module_->start(clock_.monotonic());
    ASSERT_EQ(module_->exchanges().producers().size(), 1u);
    WriteReply reply{"reply/topic", "", &northbound_, WriteOrigin::mqtt};
    ASSERT_FALSE(module_->exchanges()
                     .stage(ExchangeWrite{&module_->exchanges().producers()[0]->plan(),
                                          {{0, core::plan::Value{std::int64_t{7}}}}},
                            reply, clock_.monotonic())
                     .has_value());
    auto next = config(consumed_yaml);
    const auto line = module_->apply_plans(reload::take_plans(next));
    EXPECT_TRUE(
        line.starts_with("configuration applied: 0 exchange(s) kept, 1 started, 1 "
                         "stopped ("))
        << line;
    EXPECT_TRUE(line.ends_with("retained topic(s) cleared")) << line;
    EXPECT_EQ(module_->writes().counters().writes_cancelled, 1u);
    ASSERT_EQ(northbound_.results.size(), 1u);
    EXPECT_EQ(northbound_.results[0].error, "reloaded");
    module_->stop();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
