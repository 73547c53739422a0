// `discover`'s requester against the gateway's command port on loopback: an answer comes back
// after the challenge is met, later requests carry the token, and a node that never answers
// is said so after every attempt. The port's loop runs on its own thread.

#include "app/cli/detail/command_requester.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <utility>

#include "tests/app/support/running_command_port.hpp"
#include "tests/support/free_port.hpp"

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

class CommandRequesterTest : public testing::Test {
protected:
    CommandRequesterTest() { rig_.start(test::commands_config(node_.port, "127.0.0.0/8")); }
    void on_loop(std::function<void()> work) { rig_.on_loop(std::move(work)); }
    core::command::CommandCounters counters() { return rig_.counters(); }

    adapters::udp::Endpoint node_{0x7F000001, test::free_udp_port()};
    test::RunningCommandPort rig_;
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
    on_loop([this] { rig_.port().stop(); });
    CommandRequester requester(50ms, 2);
    const auto answer = requester.ask(core::command::CapabilitiesRequest{}, node_);
    ASSERT_FALSE(answer.ok());
    EXPECT_EQ(answer.error(), "no answer after 2 attempts of 50 ms");
    EXPECT_EQ(requester.no_answer(), answer.error());
    EXPECT_EQ(CommandRequester(500ms, 1).no_answer(), "no answer after 1 attempt of 500 ms");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
