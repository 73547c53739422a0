// The MQTT client's end_session() against a real Mosquitto: a session-bound client whose session
// is over (a pair's leader that stepped down) says its will after what it sent, drops what
// waited instead of flushing it, and connects again, with a new will, only when started again.

#include <string>

#include "tests/adapters/mqtt/client_fixture.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

ClientOptions session_bound(ClientOptions options, WillCount wills) {
    options.availability_topic.clear();
    options.session_bound = true;
    options.will = numbered_will(std::move(wills));
    return options;
}

TEST_F(ClientFixture, AnEndedSessionSaysItsWillLastAndConnectsAgainOnlyWhenStarted) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"}, "end-recorder");
    auto wills = std::make_shared<std::atomic<int>>(0);
    make_client(session_bound(options_for(broker), wills));
    on_loop([&] {
        client_->set_subscriptions({"gw/cmd"});
        client_->start();
    });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] {
        for (int i = 0; i < 10; ++i) {
            client_->publish(msg("gw/data", std::to_string(i), 1, false, false));
        }
        client_->end_session();
        // Its connection is gone: a publication now belongs to no session.
        client_->publish(msg("gw/data", "late", 1, false, false));
    });
    ASSERT_TRUE(recorder.wait_for_message("gw/will", [](auto& p) { return p == "1"; }));
    EXPECT_FALSE(client_->connected());
    EXPECT_EQ(client_->stats().queued, 0u);
    EXPECT_GE(client_->stats().discarded, 1u);

    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(2));
    const auto new_will = std::to_string(wills->load());
    EXPECT_NE(new_will, "1");
    recorder.publish("gw/cmd", "x");
    ASSERT_TRUE(wait_incoming(1));  // its subscriptions renewed on the new connection
    on_loop([&] { client_->publish(msg("gw/data", "fresh", 1, false, false)); });
    ASSERT_TRUE(recorder.wait_for_message("gw/data", [](auto& p) { return p == "fresh"; }));

    // Of the ended session, its data in order, then its will once (DISCONNECT kept the broker
    // from saying it again), then the new session's alone.
    const auto all = recorder.messages();
    std::size_t will = all.size();
    int next = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].topic == "gw/will") {
            will = i;
            break;
        }
        if (all[i].topic == "gw/data") {
            EXPECT_EQ(all[i].payload, std::to_string(next++));
        }
    }
    ASSERT_LT(will, all.size());
    for (auto i = will + 1; i < all.size(); ++i) {
        EXPECT_TRUE(all[i].topic == "gw/cmd" || all[i].payload == "fresh") << all[i].topic;
    }
    EXPECT_EQ(count_on(all, "gw/will", "1"), 1u);
    EXPECT_EQ(count_on(all, "gw/data", "late"), 0u);
}

TEST_F(ClientFixture, AnEndedSessionDropsWhatWaitedInsteadOfFlushingIt) {
    Mosquitto broker;
    test::TcpProxy proxy(broker.port());
    MqttRecorder recorder(broker.url(), {"gw/#"}, "drop-recorder");
    auto wills = std::make_shared<std::atomic<int>>(0);
    auto options = session_bound(options_for(broker), wills);
    const auto window = options.max_in_flight;
    ASSERT_TRUE(start_through(std::move(options), proxy.port()));

    // Cut off: the broker acknowledges nothing, so no more than the window is handed over and
    // the rest waits.
    proxy.stall();
    constexpr std::size_t published = 1000;
    publish_numbered("gw/data", published);
    on_loop([&] { client_->end_session(); });
    const auto stats = client_->stats();
    EXPECT_EQ(stats.queued, 0u);
    EXPECT_GE(stats.discarded, published - window);

    // The path is back: what was written before the cut may arrive, what waited never does.
    proxy.resume();
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(2));
    on_loop([&] { client_->publish(msg("gw/data", "fresh", 1, false, false)); });
    ASSERT_TRUE(recorder.wait_for_message("gw/data", [](auto& p) { return p == "fresh"; }));
    EXPECT_LE(recorder.messages_on("gw/data").size(), published - stats.discarded + 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
