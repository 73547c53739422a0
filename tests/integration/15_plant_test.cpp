// What real GE producers send (issue #13): a PLC that restarts starts its request ids again
// while its clock goes on.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

/// A PACSystems-like producer: 100 ms period, its own clock, no timeout configured.
const std::string plc_exchange = R"(  - name: plc
    direction: consume
    producer_id: 10.0.0.7
    exchange_id: 2
    length: 4
    period_ms: 100
    timeout_ms: 0
    topic: plc
    tags:
      - { name: COUNTER, address: "0.0", type: dint }
)";

/// Datagram `rid` of the PLC, stamped by its clock `seconds` + `ms` milliseconds.
std::vector<std::byte> plc_datagram(std::uint16_t rid, std::uint32_t seconds, std::uint32_t ms,
                                    std::int64_t counter) {
    return DatagramBuilder("10.0.0.7", 2, 4)
        .request_id(rid)
        .timestamp(seconds, ms * 1000000)
        .set("0.0", TagType::dint, counter)
        .build();
}

class PlantTest : public GatewayTest {
protected:
    json wait_status(const std::function<bool(const json&)>& pred) {
        const auto message = recorder_->wait_for_message(
            topic("plc/_status"), [&](const std::string& p) { return pred(json::parse(p)); }, 10s);
        EXPECT_TRUE(message.has_value())
            << "no such _status; last: " << recorder_->last(topic("plc/_status"))->payload;
        return message ? json::parse(message->payload) : json();
    }
};

TEST_F(PlantTest, AProducerRestartIsResynchronisedAtOnceAndCounted) {
    start(plc_exchange);
    // Running for a while: request ids around 20,000.
    constexpr std::uint32_t clock = 947817150;  // the PLC's clock: January 2000
    for (std::uint16_t i = 0; i < 5; ++i) {
        send(plc_datagram(static_cast<std::uint16_t>(20000 + i), clock, i * 100, 1000 + i));
    }
    expect_field(topic("plc/COUNTER"), "value", "1004");
    // The PLC restarts: ids begin again at 1, its clock has gone on by a few seconds.
    for (std::uint16_t i = 0; i < 5; ++i) {
        send(plc_datagram(static_cast<std::uint16_t>(1 + i), clock + 8, i * 100, i));
    }
    expect_field(topic("plc/COUNTER"), "value", "4");
    const auto status = wait_status([](const json& s) { return s["accepted"] == 10; });
    EXPECT_EQ(status["restarts"], 1);
    EXPECT_EQ(status["missed"], 0);
    EXPECT_EQ(status["out_of_order"], 0);
    EXPECT_EQ(status["request_id"], 5);
}

TEST_F(PlantTest, ALateDatagramIsStillDroppedWhenItsTimeDidNotMoveForward) {
    start(plc_exchange);
    constexpr std::uint32_t clock = 947817150;
    send(plc_datagram(500, clock, 500, 7));
    send(plc_datagram(499, clock, 400, 6));  // reordered on the network: older id, older time
    send(plc_datagram(501, clock, 600, 8));
    expect_field(topic("plc/COUNTER"), "value", "8");
    const auto status = wait_status([](const json& s) { return s["received"] == 3; });
    EXPECT_EQ(status["out_of_order"], 1);
    EXPECT_EQ(status["restarts"], 0);
    EXPECT_EQ(status["accepted"], 2);
}

}  // namespace
}  // namespace eip2mqtt::test
