// The MQTT client with a list of brokers: the next one after a failed attempt or a lost
// connection, back to the first after the last, and the current one in its stats.

#include "tests/adapters/mqtt/client_fixture.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

bool is_online(const std::string& payload) { return payload == "online"; }

TEST_F(ClientFixture, AFailedAttemptMovesToTheNextBroker) {
    Mosquitto gone;
    const auto gone_url = gone.url();
    gone.stop();  // nothing listens on its port now: the attempt is refused
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    auto options = options_for(broker);
    options.urls = {gone_url, broker.url()};
    make_client(std::move(options));
    on_loop([&] { client_->start(); });

    ASSERT_TRUE(wait_connected_count(1));
    EXPECT_TRUE(recorder.wait_for_message("gw/state", is_online));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.broker, broker.url());
    EXPECT_EQ(stats.connects, 1u);
}

TEST_F(ClientFixture, ALostConnectionMovesToTheNextBrokerAndWrapsAround) {
    Mosquitto first;
    Mosquitto second;
    auto options = options_for(first);
    options.urls = {first.url(), second.url()};
    make_client(std::move(options));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    EXPECT_EQ(on_loop([&] { return client_->stats(); }).broker, first.url());

    first.stop();
    ASSERT_TRUE(wait_connected_count(2));
    EXPECT_EQ(on_loop([&] { return client_->stats(); }).broker, second.url());
    {
        // Announced on the second broker, which never heard of it before.
        MqttRecorder late(second.url(), {"gw/state"});
        EXPECT_TRUE(late.wait_for_message("gw/state", is_online));
    }

    first.start();
    second.stop();
    ASSERT_TRUE(wait_connected_count(3));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.broker, first.url());
    EXPECT_EQ(stats.connects, 3u);
    EXPECT_EQ(stats.connection_losses, 2u);
}

TEST_F(ClientFixture, NoBrokerWhileDisconnected) {
    Mosquitto broker;
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    broker.stop();
    ASSERT_TRUE(wait_disconnected());
    EXPECT_EQ(on_loop([&] { return client_->stats(); }).broker, "");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
