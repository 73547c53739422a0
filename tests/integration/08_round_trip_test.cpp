// One gateway produces an exchange and consumes it back: an MQTT write comes back as the
// consumed tag's new value, through the real wire.

#include <nlohmann/json.hpp>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

class RoundTripTest : public GatewayTest {};

TEST_F(RoundTripTest, WriteComesBackAsTheConsumedValue) {
    udp_port_ = free_udp_port();
    const std::string port = std::to_string(udp_port_);
    start(ExchangeYaml::produce("out", "10.5.5.5", 42, "127.0.0.1:" + port)
              .period_ms(20)
              .tag("SETPOINT", "0.0", "dint", "writable: true, initial: 1")
              .tag("ENABLE", "4.2", "bit", "writable: true")
              .str() +
          ExchangeYaml::consume("back", "10.5.5.5", 42)
              .period_ms(20)
              .tag("SETPOINT", "0.0", "dint")
              .tag("ENABLE", "4.2", "bit")
              .str());
    expect_field(topic("back/SETPOINT"), "value", "1");
    recorder_->publish(topic("out/set"), R"({"SETPOINT":-123456,"ENABLE":true})");
    expect_field(topic("out/set/result"), "ok", "true");
    expect_field(topic("back/SETPOINT"), "value", "-123456");
    expect_field(topic("back/ENABLE"), "value", "true");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
