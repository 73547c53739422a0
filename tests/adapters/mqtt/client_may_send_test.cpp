// ClientOptions::may_send against a real Mosquitto: asked of each publication as the sender
// takes it, so what waited when the answer turned to no (a pair's leader whose lease lapsed
// while cut off from the broker) is dropped and counted, never sent once the path is back.

#include <atomic>
#include <string>

#include "tests/adapters/mqtt/client_fixture.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

TEST_F(ClientFixture, WhatMaySendNoLongerAllowsIsDroppedWhenTakenEvenIfItWaitedBefore) {
    Mosquitto broker;
    test::TcpProxy proxy(broker.port());
    MqttRecorder recorder(broker.url(), {"gw/#"}, "may-send-recorder");
    // Shared with the client, which outlives the test body's locals until TearDown stops it.
    auto leading = std::make_shared<std::atomic<bool>>(true);
    auto options = options_for(broker);
    options.may_send = [leading](const Message& message) {
        return message.topic != "gw/tag" || leading->load();
    };
    const auto window = options.max_in_flight;
    ASSERT_TRUE(start_through(std::move(options), proxy.port()));

    // Cut off: no more than the window is handed over, the rest waits in the queue.
    proxy.stall();
    constexpr std::size_t published = 1000;
    publish_numbered("gw/tag", published);
    *leading = false;
    on_loop([&] { client_->publish(msg("gw/own", "still said", 1, false, false)); });
    proxy.resume();
    ASSERT_TRUE(recorder.wait_for_message("gw/own", [](auto& p) { return p == "still said"; }));

    // What was handed over before may arrive (at most the window, and what the connection lost
    // sent again); nothing of what waited behind it.
    const auto tags = recorder.messages_on("gw/tag");
    EXPECT_LE(tags.size(), window);
    EXPECT_GE(client_->stats().discarded, published - window);
    EXPECT_EQ(client_->stats().queued, 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
