// Why the broker refused or ended the MQTT connection, named in the log: another client with
// the gateway's client id (MQTT 5 reason 0x8E, or a broker that closes the older connection
// without a reason), and a broker that does not speak MQTT 5.

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/scripted_broker.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .tag("SPEED", "0.0", "real")
                                     .str();

/// Runs a gateway (MQTT 5 unless `version` says otherwise) against `url`, with client id
/// `shared-id`.
ChildProcess gateway_for(const TempDir& dir, const std::string& url,
                         const std::string& version = "5") {
    const auto config = dir.write(
        "gateway.yaml", "gateway:\n  id: reasons-gw\n  state_dir: " + dir.path() +
                            "/state\nmqtt:\n  url: " + url + "\n  version: " + version +
                            "\n  client_id: shared-id\n  base_topic: test\neip:\n"
                            "  bind: 127.0.0.1\n  port: " +
                            std::to_string(free_udp_port()) + "\nexchanges:\n" + one_exchange);
    return ChildProcess({gateway_binary(), "run", "-c", config});
}

const std::string refused_mqtt5 = "the broker refused MQTT 5";
const std::string version_fix = "set mqtt.version: 3.1.1";

TEST(ConnectionReasons, ABrokerThatClosesOnAnMqtt5ConnectIsNamedWithTheFix) {
    ScriptedBroker rabbit({});  // RabbitMQ 3.10: the connection closes, no CONNACK
    TempDir dir;
    auto gateway = gateway_for(dir, rabbit.url());
    EXPECT_TRUE(gateway.wait_for_output(version_fix, 30s)) << gateway.output();
    EXPECT_NE(gateway.output().find(refused_mqtt5), std::string::npos) << gateway.output();
    EXPECT_EQ(rabbit.protocol_level(), 5);
}

TEST(ConnectionReasons, AnMqtt311RefusalOfTheProtocolVersionIsNamedWithTheFix) {
    ScriptedBroker old_broker({0x20, 0x02, 0x00, 0x01});  // CONNACK: unacceptable version
    TempDir dir;
    auto gateway = gateway_for(dir, old_broker.url());
    EXPECT_TRUE(gateway.wait_for_output(version_fix, 30s)) << gateway.output();
    EXPECT_NE(gateway.output().find(refused_mqtt5 + " (it answered in MQTT 3.1.1"),
              std::string::npos)
        << gateway.output();
}

TEST(ConnectionReasons, WithMqtt311ABrokerThatClosesGetsNoVersionAdvice) {
    ScriptedBroker closing({});
    TempDir dir;
    auto gateway = gateway_for(dir, closing.url(), "3.1.1");
    ASSERT_TRUE(gateway.wait_for_output("cannot connect to", 30s)) << gateway.output();
    EXPECT_EQ(gateway.output().find(version_fix), std::string::npos) << gateway.output();
}

TEST(ConnectionReasons, ASessionTakenOverNamesTheSharedClientId) {
    // CONNACK (MQTT 5, success, no properties); then, once the gateway sent its first packet,
    // DISCONNECT with reason 0x8E as Mosquitto 2.0.15 and later send to the older connection.
    ScriptedBroker broker({0x20, 0x03, 0x00, 0x00, 0x00}, {0xE0, 0x02, 0x8E, 0x00});
    TempDir dir;
    auto gateway = gateway_for(dir, broker.url());
    EXPECT_TRUE(
        gateway.wait_for_output("another client connected with the same client id "
                                "'shared-id' (MQTT 5 reason 0x8E",
                                30s))
        << gateway.output();
}

class SharedClientIdTest : public GatewayTest {};

TEST_F(SharedClientIdTest, ASecondClientWithTheSameIdIsNamedAsTheCause) {
    start(one_exchange, "  client_id: shared-id\n");
    // A real second client with the gateway's id, reconnecting whenever it is put out (Debian's
    // Mosquitto 2.0.11 closes the older connection without reason 0x8E).
    ChildProcess twin({"/usr/bin/mosquitto_sub", "-h", "127.0.0.1", "-p",
                       std::to_string(broker_->port()), "-i", "shared-id", "-V", "mqttv5", "-t",
                       "twin/none"});
    EXPECT_TRUE(gateway_->wait_for_output("same client id 'shared-id'", 60s)) << gateway_->output();
    twin.signal(SIGTERM);
    twin.wait(10s);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
