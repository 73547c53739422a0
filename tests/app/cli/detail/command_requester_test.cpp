// `discover`'s requester against the gateway's command port on loopback: an answer comes back
// after the challenge is met, later requests carry the token, and a node that never answers
// is said so after every attempt. The port's loop runs on its own thread.

#include "app/cli/detail/command_requester.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <functional>
#include <future>
#include <thread>

#include "eip2mqtt/app/command_port/command_port.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/recording_write_handler.hpp"
#include "tests/support/free_port.hpp"

namespace eip2mqtt::app::detail {
namespace {

using namespace std::chrono_literals;

class CommandRequesterTest : public testing::Test {
protected:
    CommandRequesterTest() {
        core::config::Config config;
        config.eip.bind = "127.0.0.1";
        config.eip.commands.enabled = true;
        config.eip.commands.port = node_.port;
        config.eip.commands.allow =
            std::vector<core::net::Subnet>{*core::net::parse_subnet("127.0.0.0/8")};
        port_ = command_port::make_command_port(config, loop_.get_executor(), exchanges_, writes_,
                                                clock_);
        port_->start(clock_.monotonic());
        thread_ = std::thread([this] { loop_.run(); });
    }
    ~CommandRequesterTest() override {
        on_loop([this] { port_->stop(); });
        guard_.reset();
        thread_.join();
    }
    void on_loop(std::function<void()> work) {
        std::promise<void> done;
        boost::asio::post(loop_, [&] {
            work();
            done.set_value();
        });
        ASSERT_EQ(done.get_future().wait_for(10s), std::future_status::ready);
    }
    core::command::CommandCounters counters() {
        core::command::CommandCounters copy;
        on_loop([&] {
            DatagramCounters datagrams;
            WriteCounters writes;
            adapters::mqtt::ClientStats mqtt;
            MetricsSources sources{datagrams, writes, mqtt};
            port_->add_metrics(sources);
            copy = *sources.commands;
        });
        return copy;
    }

    boost::asio::io_context loop_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard_{
        loop_.get_executor()};
    test::RecordingNorthbound northbound_;
    ImageSaveTotals totals_;
    Exchanges exchanges_{loop_.get_executor(), ExchangesOptions{}, northbound_, totals_};
    test::RecordingWriteHandler writes_;
    test::FakeClock clock_;
    adapters::udp::Endpoint node_{0x7F000001, test::free_udp_port()};
    std::unique_ptr<Module> port_;
    std::thread thread_;
};

TEST_F(CommandRequesterTest, AnAnswerComesAfterTheChallengeAndLaterRequestsCarryTheToken) {
    CommandRequester requester(2s, 3);
    for (int i = 0; i < 2; ++i) {
        const auto answer = requester.ask(core::command::CapabilitiesRequest{}, node_);
        ASSERT_TRUE(answer.ok()) << answer.error();
        EXPECT_EQ(answer->header.status, 0);
        EXPECT_EQ(std::get<core::command::Capabilities>(answer->body).producer_id.value,
                  0x7F000001u);
    }
    EXPECT_EQ(counters().challenged, 1u);  // the second request carried the token
}

TEST_F(CommandRequesterTest, ANodeThatNeverAnswersIsSaidSoAfterEveryAttempt) {
    on_loop([this] { port_->stop(); });
    CommandRequester requester(50ms, 2);
    const auto answer = requester.ask(core::command::CapabilitiesRequest{}, node_);
    ASSERT_FALSE(answer.ok());
    EXPECT_EQ(answer.error(), "no answer after 2 attempts of 50 ms");
    EXPECT_EQ(requester.no_answer(), answer.error());
    EXPECT_EQ(CommandRequester(500ms, 1).no_answer(), "no answer after 1 attempt of 500 ms");
}

}  // namespace
}  // namespace eip2mqtt::app::detail
