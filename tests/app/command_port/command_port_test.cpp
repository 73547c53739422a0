// The command port as a module of the gateway: made only when enabled, it answers on its UDP
// port from the running exchanges once started, takes a new policy on reload, and counts what
// it refused. The loop runs on its own thread; the port is touched on it only.

#include "eip2mqtt/app/command_port/command_port.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <functional>
#include <future>
#include <thread>

#include "eip2mqtt/app/health/metrics.hpp"
#include "tests/support/command_client.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/recording_write_handler.hpp"
#include "tests/support/free_port.hpp"

namespace eip2mqtt::app::command_port {
namespace {

using namespace std::chrono_literals;
using core::command::PduType;

core::config::Config commands_config(std::uint16_t port, const char* allow) {
    core::config::Config config;
    config.eip.bind = "127.0.0.1";
    config.eip.commands.enabled = true;
    config.eip.commands.port = port;
    config.eip.commands.allow = std::vector<core::net::Subnet>{*core::net::parse_subnet(allow)};
    return config;
}

class CommandPortTest : public testing::Test {
protected:
    ~CommandPortTest() override {
        if (port_) on_loop([this] { port_->stop(); });
        guard_.reset();
        if (thread_.joinable()) thread_.join();
    }
    void start(const core::config::Config& config) {
        port_ = make_command_port(config, loop_.get_executor(), exchanges_, writes_, clock_);
        ASSERT_NE(port_, nullptr);
        port_->start(clock_.monotonic());
        thread_ = std::thread([this] { loop_.run(); });
    }
    /// Runs `work` on the loop and waits for it.
    void on_loop(std::function<void()> work) {
        std::promise<void> done;
        boost::asio::post(loop_, [&] {
            work();
            done.set_value();
        });
        ASSERT_EQ(done.get_future().wait_for(10s), std::future_status::ready);
    }
    std::uint64_t refused() {
        std::uint64_t count = 0;
        on_loop([&] {
            DatagramCounters datagrams;
            WriteCounters writes;
            adapters::mqtt::ClientStats mqtt;
            MetricsSources sources{datagrams, writes, mqtt};
            port_->add_metrics(sources);
            count = sources.commands->refused;
        });
        return count;
    }

    boost::asio::io_context loop_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard_{
        loop_.get_executor()};
    test::RecordingNorthbound northbound_;
    ImageSaveTotals totals_;
    Exchanges exchanges_{loop_.get_executor(), ExchangesOptions{}, northbound_, totals_};
    test::RecordingWriteHandler writes_;
    test::FakeClock clock_;
    std::unique_ptr<Module> port_;
    std::thread thread_;
    std::uint16_t commands_port_ = test::free_udp_port();
};

TEST_F(CommandPortTest, NoPortUnlessEnabled) {
    auto config = commands_config(commands_port_, "127.0.0.0/8");
    config.eip.commands.enabled = false;
    EXPECT_EQ(make_command_port(config, loop_.get_executor(), exchanges_, writes_, clock_),
              nullptr);
}

TEST_F(CommandPortTest, OnceStartedItAnswersAsTheNodeOfItsBindAddress) {
    start(commands_config(commands_port_, "127.0.0.0/8"));
    test::CommandClient client;
    const auto response = client.ask(commands_port_, PduType::capabilities_request,
                                     core::command::CapabilitiesRequest{});
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, 0);
    const auto& node = std::get<core::command::Capabilities>(response->body);
    EXPECT_EQ(node.producer_id.value, 0x7F000001u);
    EXPECT_TRUE(node.identification.starts_with("eip2mqtt ")) << node.identification;
    EXPECT_EQ(refused(), 0u);
}

TEST_F(CommandPortTest, ANewPolicyRefusesWhomItNoLongerAllows) {
    start(commands_config(commands_port_, "127.0.0.0/8"));
    on_loop([this] { port_->apply(commands_config(commands_port_, "127.0.0.2/32")); });
    test::CommandClient refused_client;  // 127.0.0.1
    refused_client.udp().send_to(commands_port_,
                                 refused_client.request(PduType::capabilities_request,
                                                        core::command::CapabilitiesRequest{}));
    // Sent after it to the same socket, so handled after it: once answered, the first was seen.
    test::CommandClient allowed_client(0x7F000002);
    const auto response = allowed_client.ask(commands_port_, PduType::capabilities_request,
                                             core::command::CapabilitiesRequest{});
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, 0);
    EXPECT_EQ(refused(), 1u);
    EXPECT_FALSE(refused_client.udp().receive(0ms).has_value());
}

}  // namespace
}  // namespace eip2mqtt::app::command_port
