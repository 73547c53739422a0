// `sim`: the values it sends (bits toggle, integers ramp, reals follow a wave, arrays and
// strings), the datagrams it builds from them stamped with its clock's time, the production that
// spreads the first sends over the period and then keeps it, what its command port says about
// the exchanges, which port it answers on, and run_sim's refusals and a short run on loopback.

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <thread>

#include "app/cli/detail/simulator.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/app/support/logger_restore.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/command_client.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;
using core::plan::Value;

/// Two consumed exchanges (periods 10 and 20 ms) and a produced one, sent to `port`.
std::string sim_yaml(std::uint16_t port) {
    return "mqtt:\n  url: tcp://a:1883\neip:\n  port: " + std::to_string(port) +
           "\nexchanges:\n"
           "  - { name: a, producer_id: 10.0.0.1, exchange_id: 1, length: 4, period_ms: 10,\n"
           "      tags: [ { name: N, address: \"0.0\", type: int } ] }\n"
           "  - { name: b, producer_id: 10.0.0.1, exchange_id: 2, length: 8, period_ms: 20 }\n"
           "  - { name: out, producer_id: 10.0.0.9, exchange_id: 3, length: 4,\n"
           "      direction: produce, destination: 127.0.0.1 }\n";
}

core::config::Config load(const std::string& yaml) {
    test::TempDir dir;
    auto loaded = adapters::yaml::load_config(dir.write("sim.yaml", yaml));
    EXPECT_TRUE(loaded.ok());
    return std::move(loaded).value();
}

/// run_sim, which sets up its own logger each time.
int sim(const SimOptions& options) {
    test::LoggerRestore::fresh();
    return run_sim(options);
}

core::plan::TagSpec bit(std::uint8_t number) {
    auto tag = test::test_tag("B", 0, TagType::bit);
    tag.address.bit = number;
    return tag;
}

TEST(SimValues, BitsToggleEveryTenCyclesEachAtItsBitsPhase) {
    EXPECT_EQ(simulated_value(bit(0), 0, 0), Value{true});
    EXPECT_EQ(simulated_value(bit(0), 9, 0), Value{true});
    EXPECT_EQ(simulated_value(bit(0), 10, 0), Value{false});
    EXPECT_EQ(simulated_value(bit(1), 0, 0), Value{false});
    EXPECT_EQ(simulated_value(bit(0), 3, 1), Value{false});  // the tag's index moves it 7 cycles
}

TEST(SimValues, IntegersRampAndWrapRealsFollowAWave) {
    const auto tag = [](TagType type) { return test::test_tag("T", 0, type); };
    EXPECT_EQ(simulated_value(tag(TagType::int_), 0, 0), Value{std::int64_t{-1000}});
    EXPECT_EQ(simulated_value(tag(TagType::int_), 1, 0), Value{std::int64_t{-999}});
    EXPECT_EQ(simulated_value(tag(TagType::int_), 2000, 0), Value{std::int64_t{-1000}});
    EXPECT_EQ(simulated_value(tag(TagType::byte), 300, 0), Value{std::uint64_t{44}});
    EXPECT_EQ(simulated_value(tag(TagType::byte), 0, 2), Value{std::uint64_t{14}});
    EXPECT_EQ(simulated_value(tag(TagType::word), 65536, 0), Value{std::uint64_t{0}});
    EXPECT_EQ(simulated_value(tag(TagType::dint), 1, 0), Value{std::int64_t{-99000}});
    EXPECT_EQ(simulated_value(tag(TagType::udint), 2, 0), Value{std::uint64_t{200000}});
    EXPECT_EQ(simulated_value(tag(TagType::lint), 1, 0), Value{std::int64_t{-499000000}});
    EXPECT_EQ(simulated_value(tag(TagType::lreal), 4, 0), Value{1002.0});
    EXPECT_EQ(simulated_value(tag(TagType::real), 0, 0), Value{100.0f});
    EXPECT_EQ(simulated_value(tag(TagType::real), 10, 0), Value{123.971f});  // 100 + 50 sin(0.5)
}

TEST(SimValues, AScaledTagSweepsItsEngineeringSpanInRawValues) {
    auto level = test::test_tag("L", 0, TagType::int_);
    level.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::linear, {0, 32000}, {0, 100}, 1, 0, false, std::nullopt};
    EXPECT_EQ(simulated_value(level, 0, 0), Value{std::int64_t{16000}});  // 50 %
    for (std::uint64_t cycle = 0; cycle < 200; ++cycle) {
        const auto raw = std::get<std::int64_t>(simulated_value(level, cycle, 0));
        EXPECT_GE(raw, 1600) << cycle;   // 5 %
        EXPECT_LE(raw, 30400) << cycle;  // 95 %
    }
    auto oil = test::test_tag("O", 0, TagType::int_);  // no span: the raw ramp
    oil.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::gain_offset, {}, {}, 0.1, -40, false, std::nullopt};
    EXPECT_EQ(simulated_value(oil, 0, 0), Value{std::int64_t{-1000}});
}

TEST(SimValues, AnArraysElementsEachMoveAndAStringFitsItsField) {
    auto temps = test::test_tag("T", 0, TagType::int_);
    temps.count = 3;
    EXPECT_EQ(core::plan::to_json(simulated_value(temps, 0, 0)), "[-1000,-997,-994]");
    auto batch = test::test_tag("B", 0, TagType::string);
    batch.count = 8;
    EXPECT_EQ(simulated_value(batch, 0, 0), core::plan::make_text("BATCH-10"));
    EXPECT_EQ(simulated_value(batch, 50, 0), core::plan::make_text("BATCH-10"));  // cut to 8
    batch.count = 10;
    EXPECT_EQ(simulated_value(batch, 50, 0), core::plan::make_text("BATCH-1001"));
}

class SimTest : public ::testing::Test {
protected:
    SimTest() { clock_.advance(1500ms); }  // 2026-01-01T00:00:01.5Z

    boost::asio::io_context loop_;
    test::FakeClock clock_;
    test::UdpClient plc_side_;  // where the simulated datagrams go
    core::config::Config config_ = load(sim_yaml(plc_side_.port()));
};

TEST_F(SimTest, OnlyTheConsumedExchangesAreSimulated) {
    const auto exchanges = simulated_exchanges(config_, loop_);
    ASSERT_EQ(exchanges.size(), 2u);
    EXPECT_EQ(exchanges[0].plan.spec.name, "a");
    EXPECT_EQ(exchanges[1].plan.spec.name, "b");
    EXPECT_EQ(exchanges[1].header.exchange_id, 2u);
    EXPECT_EQ(exchanges[1].datagram.size(), core::wire::header_size + 8);
}

TEST_F(SimTest, EachDatagramCarriesItsCyclesValuesTheClocksTimeAndTheNextRequestId) {
    auto exchanges = simulated_exchanges(config_, loop_);
    auto& sim = exchanges[0];
    sim.header.request_id = 65535;
    for (const std::uint16_t rid : {65535, 0}) {
        const auto decoded = core::wire::decode_datagram(next_datagram(sim, clock_.wall()));
        ASSERT_TRUE(decoded.ok());
        const auto& header = decoded.value().header;
        EXPECT_EQ(header.request_id, rid);
        EXPECT_EQ(header.time_s, 1767225601u);
        EXPECT_EQ(header.time_ns, 500000000u);
        EXPECT_EQ(header.producer_id, *core::wire::parse_producer_id("10.0.0.1"));
        const auto value = core::plan::decode_value(decoded.value().data, TagType::int_, {0, 0});
        EXPECT_EQ(value, Value{std::int64_t{rid == 0 ? -999 : -1000}});
    }
    EXPECT_EQ(sim.cycle, 2u);
}

TEST_F(SimTest, TheFirstSendsAreSpreadOverThePeriodFromTheClocksNow) {
    auto exchanges = simulated_exchanges(config_, loop_);
    clock_.set_monotonic(std::chrono::steady_clock::now() + 1h);  // never due during the test
    adapters::udp::Sender sender(loop_.get_executor(), {});
    Production production(sender, {0x7F000001, plc_side_.port()}, clock_);
    production.start(exchanges);
    EXPECT_EQ(exchanges[0].deadline, clock_.monotonic());
    EXPECT_EQ(exchanges[1].deadline, clock_.monotonic() + 10ms);  // 20 ms * 1 / 2
}

TEST_F(SimTest, ProductionSendsEachExchangeOnItsPeriodStampedWithTheClock) {
    auto exchanges = simulated_exchanges(config_, loop_);
    exchanges.resize(1);
    clock_.set_monotonic(std::chrono::steady_clock::now());
    adapters::udp::Sender sender(loop_.get_executor(), {});
    Production production(sender, {0x7F000001, plc_side_.port()}, clock_);
    production.start(exchanges);
    std::thread loop([this] { loop_.run(); });
    std::vector<core::wire::Header> headers;
    for (int i = 0; i < 3; ++i) {
        const auto bytes = plc_side_.receive(10s);
        if (!bytes) break;
        headers.push_back(core::wire::decode_datagram(*bytes).value().header);
    }
    loop_.stop();
    loop.join();
    ASSERT_EQ(headers.size(), 3u);
    for (std::uint16_t i = 0; i < 3; ++i) {
        EXPECT_EQ(headers[i].request_id, i);
        EXPECT_EQ(headers[i].time_s, 1767225601u);
        EXPECT_EQ(headers[i].time_ns, 500000000u);
    }
    // Absolute deadlines: the next is a whole number of periods after the first, never drifting.
    EXPECT_EQ(exchanges[0].deadline,
              clock_.monotonic() + static_cast<long>(exchanges[0].cycle) * 10ms);
}

TEST_F(SimTest, AnExchangeIsViewedAsProducedWithItsImageOnceSent) {
    auto exchanges = simulated_exchanges(config_, loop_);
    auto& sim = exchanges[0];
    const adapters::udp::Endpoint target{0x7F000001, 18246};
    auto view = sim_view(sim, target, {}, clock_.wall());
    EXPECT_EQ(view.mode, core::command::ExchangeMode::produced);
    EXPECT_EQ(view.state, core::command::ExchangeState::active);
    EXPECT_EQ(view.config_time_s, 1767225601u);
    EXPECT_EQ(view.destination, 0x7F000001u);
    EXPECT_EQ(view.port, 18246);
    EXPECT_TRUE(view.image.empty());
    EXPECT_EQ(view.messages, 0u);
    next_datagram(sim, clock_.wall() + 1s);
    sim.sent = 1;
    view = sim_view(sim, target, {}, clock_.wall());
    EXPECT_EQ(view.messages, 1u);
    EXPECT_EQ(view.image.size(), 4u);
    EXPECT_EQ(view.time_s, 1767225602u);
    EXPECT_EQ(view.time_ns, 500000000u);
}

TEST_F(SimTest, TheCommandPortIsTheOptionsElseTheConfigurationsWhenEnabled) {
    SimOptions options;
    config_.eip.commands.port = 7937;
    config_.eip.commands.enabled = false;
    EXPECT_EQ(commands_port(options, config_), 0);
    config_.eip.commands.enabled = true;
    EXPECT_EQ(commands_port(options, config_), 7937);
    options.commands_port = 0;
    EXPECT_EQ(commands_port(options, config_), 0);
    options.commands_port = 17937;
    EXPECT_EQ(commands_port(options, config_), 17937);
}

TEST_F(SimTest, TheCommandPortSaysTheExchangesWereConfiguredAtTheClocksTime) {
    const auto exchanges = simulated_exchanges(config_, loop_);
    config_.eip.bind = "127.0.0.1";
    config_.eip.commands.allow =
        std::vector<core::net::Subnet>{*core::net::parse_subnet("127.0.0.0/8")};
    const auto port = test::free_udp_port();
    auto commands = start_commands(loop_, config_, port, exchanges, {0x7F000001, 18246}, clock_);
    clock_.advance(1h);  // later questions do not move the configuration's time
    boost::asio::executor_work_guard guard(loop_.get_executor());
    std::thread loop([this] { loop_.run(); });
    test::CommandClient client;
    const auto answer = client.ask(port, core::command::PduType::statistics_request,
                                   core::command::StatisticsRequest{exchanges[1].plan.key()});
    boost::asio::post(loop_, [&] { commands.socket->stop(); });
    guard.reset();
    loop.join();
    ASSERT_TRUE(answer.has_value());
    const auto& statistics = std::get<core::command::ExchangeStatistics>(answer->body);
    EXPECT_EQ(statistics.config_time_s, 1767225601u);
    EXPECT_EQ(statistics.length, 8u);
}

TEST(RunSim, RefusesABadConfigurationATargetItCannotResolveAndNothingToSimulate) {
    const test::LoggerRestore logger;
    test::TempDir dir;
    SimOptions options;
    options.log_level = "off";
    options.config_path = dir.path() + "/missing.yaml";
    EXPECT_EQ(sim(options), 1);
    options.config_path = dir.write("sim.yaml", sim_yaml(18246));
    options.target = "127.0.0.1:0";  // no port 0
    EXPECT_EQ(sim(options), 1);
    options.target = "127.0.0.1";
    options.config_path =
        dir.write("produced.yaml",
                  "mqtt:\n  url: tcp://a:1883\nexchanges:\n"
                  "  - { name: out, producer_id: 10.0.0.9, exchange_id: 3, length: 4,\n"
                  "      direction: produce, destination: 127.0.0.1 }\n");
    EXPECT_EQ(sim(options), 1);
}

TEST(RunSim, SendsTheConsumedExchangesToTheTargetUntilItsDuration) {
    const test::LoggerRestore logger;
    test::TempDir dir;
    test::UdpClient gateway_side;
    SimOptions options;
    options.log_level = "off";
    options.config_path = dir.write("sim.yaml", sim_yaml(18246));
    options.port = gateway_side.port();  // over eip.port
    options.commands_port = 0;
    options.duration_s = 0.2;
    EXPECT_EQ(sim(options), 0);
    const auto bytes = gateway_side.receive(5s);
    ASSERT_TRUE(bytes.has_value());
    const auto header = core::wire::decode_datagram(*bytes).value().header;
    EXPECT_EQ(header.producer_id, *core::wire::parse_producer_id("10.0.0.1"));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
