// One gateway produces an exchange and consumes it back: an MQTT write comes back as the
// consumed tag's new value, through the real wire.

#include <nlohmann/json.hpp>

#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

class RoundTripTest : public GatewayTest {};

TEST_F(RoundTripTest, WriteComesBackAsTheConsumedValue) {
    udp_port_ = free_udp_port();
    const std::string port = std::to_string(udp_port_);
    start(R"(  - name: out
    direction: produce
    producer_id: 10.5.5.5
    exchange_id: 42
    destination: 127.0.0.1:)" +
          port + R"(
    period_ms: 20
    topic: out
    tags:
      - { name: SETPOINT, address: "0.0", type: dint, writable: true, initial: 1 }
      - { name: ENABLE, address: "4.2", type: bit, writable: true }
  - name: back
    direction: consume
    producer_id: 10.5.5.5
    exchange_id: 42
    period_ms: 20
    topic: back
    tags:
      - { name: SETPOINT, address: "0.0", type: dint }
      - { name: ENABLE, address: "4.2", type: bit }
)");
    expect_field(topic("back/SETPOINT"), "value", "1");
    recorder_->publish(topic("out/set"), R"({"SETPOINT":-123456,"ENABLE":true})");
    expect_field(topic("out/set/result"), "ok", "true");
    expect_field(topic("back/SETPOINT"), "value", "-123456");
    expect_field(topic("back/ENABLE"), "value", "true");
}

}  // namespace
}  // namespace eip2mqtt::test
