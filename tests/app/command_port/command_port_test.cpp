// The command port as a module of the gateway: made only when enabled, it answers on its UDP
// port from the running exchanges once started, takes a new policy on reload, and counts what
// it refused. The loop runs on its own thread; the port is touched on it only.

#include "eip2mqtt/app/command_port/command_port.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <utility>

#include "tests/app/support/running_command_port.hpp"
#include "tests/support/command_client.hpp"
#include "tests/support/free_port.hpp"

namespace eip2mqtt::app::command_port {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::PduType;

using test::commands_config;

class CommandPortTest : public testing::Test {
protected:
    void start(const core::config::Config& config) { rig_.start(config); }
    void on_loop(std::function<void()> work) { rig_.on_loop(std::move(work)); }
    std::uint64_t refused() { return rig_.counters().refused; }

    test::RunningCommandPort rig_;
    std::uint16_t commands_port_ = test::free_udp_port();
};

TEST_F(CommandPortTest, NoPortUnlessEnabled) {
    auto config = commands_config(commands_port_, "127.0.0.0/8");
    config.eip.commands.enabled = false;
    EXPECT_EQ(rig_.make(config), nullptr);
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
    on_loop([this] { rig_.port().apply(commands_config(commands_port_, "127.0.0.2/32")); });
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::command_port
