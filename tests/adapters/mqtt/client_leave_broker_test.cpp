// The MQTT client's way out of a broker, against real Mosquittos: with disconnect_with_will
// over MQTT 5 a DISCONNECT carries the reason Disconnect with Will Message (0x04), so the
// broker says the will after the client said it (Sparkplug B 3.0's NDEATH), where MQTT 3.1.1
// has no such reason and the client's own is the only one; leave_broker() ends the session
// there and connects to the next broker of the list, with a new will.

#include <string>

#include "tests/adapters/mqtt/client_fixture.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

ClientOptions saying_its_will(ClientOptions options, WillCount wills, int version) {
    options.availability_topic.clear();
    options.session_bound = true;
    options.will = numbered_will(std::move(wills));
    options.disconnect_with_will = true;
    options.version = version;
    return options;
}

class ClientLeaveBrokerTest : public ClientFixture {
protected:
    /// Ends the first session with end_session(), starts a second one and has its `fresh`
    /// publication arrive: the broker handled the first DISCONNECT before it. How many times
    /// the first will ("1") reached a subscriber.
    std::size_t wills_of_an_ended_session(int version) {
        Mosquitto broker;
        MqttRecorder recorder(broker.url(), {"gw/#"}, "leave-recorder");
        auto wills = std::make_shared<std::atomic<int>>(0);
        make_client(saying_its_will(options_for(broker), wills, version));
        on_loop([&] { client_->start(); });
        EXPECT_TRUE(wait_connected_count(1));
        on_loop([&] { client_->end_session(); });
        on_loop([&] { client_->start(); });
        EXPECT_TRUE(wait_connected_count(2));
        on_loop([&] { client_->publish(msg("gw/data", "fresh", 1, false, false)); });
        EXPECT_TRUE(recorder.wait_for_message("gw/data", [](auto& p) { return p == "fresh"; }));
        return count_on(recorder.messages(), "gw/will", "1");
    }
};

TEST_F(ClientLeaveBrokerTest, OverMqtt5TheBrokerSaysTheWillAfterTheClient) {
    EXPECT_EQ(wills_of_an_ended_session(5), 2u);
}

TEST_F(ClientLeaveBrokerTest, OverMqtt311TheClientsOwnIsTheOnlyOne) {
    EXPECT_EQ(wills_of_an_ended_session(3), 1u);
}

TEST_F(ClientLeaveBrokerTest, AStopSaysTheWillAndTheBrokerSaysItAgain) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"}, "stop-recorder");
    auto wills = std::make_shared<std::atomic<int>>(0);
    make_client(saying_its_will(options_for(broker), wills, 5));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    stop_loop();
    client_->stop(std::chrono::seconds(2));
    EXPECT_TRUE(recorder.wait_for(has_n_on("gw/will", 2), kTimeout));
    EXPECT_EQ(count_on(recorder.messages(), "gw/will", "1"), 2u);
}

TEST_F(ClientLeaveBrokerTest, LeavingSaysTheWillThereAndConnectsToTheNextBrokerWithANewOne) {
    Mosquitto first;
    Mosquitto second;
    MqttRecorder on_first(first.url(), {"gw/#"}, "first-recorder");
    auto wills = std::make_shared<std::atomic<int>>(0);
    auto options = saying_its_will(options_for(first), wills, 5);
    options.urls = {first.url(), second.url()};
    make_client(std::move(options));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] { client_->leave_broker(); });
    ASSERT_TRUE(wait_connected_count(2));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.broker, second.url());
    EXPECT_EQ(stats.connection_losses, 0u);  // left on purpose, not lost
    EXPECT_TRUE(on_first.wait_for_message("gw/will", [](auto& p) { return p == "1"; }));
    EXPECT_EQ(wills->load(), 2);  // the second connection's own

    // The last broker's next is the first again.
    on_loop([&] { client_->leave_broker(); });
    ASSERT_TRUE(wait_connected_count(3));
    EXPECT_EQ(on_loop([&] { return client_->stats(); }).broker, first.url());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
