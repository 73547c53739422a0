// The availability topic, clean stops, kills, and retained state after a broker restart.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .timeout_ms(0)
                                     .topic("area/pump")
                                     .tag("SPEED", "0.0", "real")
                                     .str();

std::vector<std::byte> speed_datagram(std::uint16_t rid, float speed) {
    return DatagramBuilder("10.0.0.2", 7, 4)
        .request_id(rid)
        .set("0.0", TagType::real, speed)
        .build();
}

class AvailabilityTest : public GatewayTest {};

TEST_F(AvailabilityTest, CleanStopPublishesOfflineAndExitsZero) {
    start(one_exchange);
    const auto from = recorder_->count();
    gateway_->signal(SIGTERM);
    const auto status = gateway_->wait(std::chrono::seconds(10));
    ASSERT_TRUE(status.has_value());
    EXPECT_EQ(*status, 0);
    EXPECT_TRUE(recorder_->wait_for_message(
        availability_topic(), [](const std::string& p) { return p == "offline"; },
        std::chrono::seconds(5), from));
}

TEST_F(AvailabilityTest, KilledGatewayIsReportedOfflineByTheWill) {
    start(one_exchange);
    const auto from = recorder_->count();
    gateway_->signal(SIGKILL);
    gateway_->wait(std::chrono::seconds(5));
    // The broker publishes the will when it notices the dead connection (at once on loopback:
    // the kernel closes the socket).
    EXPECT_TRUE(recorder_->wait_for_message(
        availability_topic(), [](const std::string& p) { return p == "offline"; },
        std::chrono::seconds(10), from));
}

TEST_F(AvailabilityTest, RetainedStateIsRepublishedAfterBrokerRestart) {
    start(one_exchange);
    send(speed_datagram(1, 1450.5f));
    expect_field(topic("area/pump/SPEED"), "value", "1450.5");

    // Without persistence, the restarted broker has forgotten every retained message.
    recorder_.reset();
    broker_->stop();
    broker_->start();

    // A fresh subscriber sees the gateway come back online and the retained value again,
    // without any new datagram.
    recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"test/#"});
    wait_online();
    expect_field(topic("area/pump/SPEED"), "value", "1450.5");
    expect_field(topic("area/pump/_status"), "state", "\"ok\"");

    // And it keeps consuming.
    send(speed_datagram(2, 1500.0f));
    expect_field(topic("area/pump/SPEED"), "value", "1500.0");
}

TEST_F(AvailabilityTest, MetricsArePublishedPeriodically) {
    start(one_exchange);
    send(speed_datagram(1, 1.0f));
    const auto metrics = recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return nlohmann::json::parse(p)["accepted"] == 1;
    });
    ASSERT_TRUE(metrics.has_value());
    const auto j = nlohmann::json::parse(metrics->payload);
    EXPECT_EQ(j["datagrams"], 1);
    EXPECT_TRUE(j["dropped"].is_object());
    EXPECT_GE(j["published"].get<int>(), 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
