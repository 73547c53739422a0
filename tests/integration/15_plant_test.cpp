// What real GE producers send: a PLC whose clock was never set, and one that
// restarts: its request ids start again while its clock goes on.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

/// A PACSystems-like producer: 100 ms period, its own clock, no timeout configured.
ExchangeYaml plc_exchange() {
    return ExchangeYaml::consume("plc", "10.0.0.7", 2)
        .length(4)
        .period_ms(100)
        .timeout_ms(0)
        .tag("COUNTER", "0.0", "dint");
}

/// The PLC's clock without SNTP: January 2000, as a real capture shows.
constexpr std::uint32_t clock_2000 = 947817150;

std::int64_t now_ms() {
    return std::chrono::duration_cast<std::chrono::milliseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

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
    start(plc_exchange().str());
    // Running for a while: request ids around 20,000.
    constexpr std::uint32_t clock = clock_2000;
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
    start(plc_exchange().str());
    constexpr std::uint32_t clock = clock_2000;
    send(plc_datagram(500, clock, 500, 7));
    send(plc_datagram(499, clock, 400, 6));  // reordered on the network: older id, older time
    send(plc_datagram(501, clock, 600, 8));
    expect_field(topic("plc/COUNTER"), "value", "8");
    const auto status = wait_status([](const json& s) { return s["received"] == 3; });
    EXPECT_EQ(status["out_of_order"], 1);
    EXPECT_EQ(status["restarts"], 0);
    EXPECT_EQ(status["accepted"], 2);
}

// The default `timestamp: auto`: a clock 26 years off gives its tags the receive time, and
// `_status` says why, with the offset; the change is logged once, not per datagram.
TEST_F(PlantTest, AnUnsynchronisedProducerClockGivesItsTagsTheReceiveTime) {
    start(plc_exchange().str());
    const auto before = now_ms();
    for (std::uint16_t i = 1; i <= 20; ++i) send(plc_datagram(i, clock_2000, i, 100 + i));
    const auto value = expect_field(topic("plc/COUNTER"), "value", "120");
    const auto after = now_ms();
    const auto stamp = json::parse(value.payload)["timestamp"].get<std::int64_t>();
    EXPECT_GE(stamp, before);
    EXPECT_LE(stamp, after);
    const auto status = wait_status([](const json& s) { return s["accepted"] == 20; });
    EXPECT_EQ(status["clock"], "unsynced");
    const auto offset = status["clock_offset_ms"].get<std::int64_t>();
    EXPECT_LE(offset, std::int64_t{clock_2000} * 1000 + 20 - before);
    EXPECT_GE(offset, std::int64_t{clock_2000} * 1000 - after);
    const auto log = gateway_->output();
    const std::string line = "the producer's clock is";
    ASSERT_NE(log.find(line), std::string::npos) << log;
    EXPECT_EQ(log.find(line), log.rfind(line)) << "logged more than once:\n" << log;
}

// A synchronised producer's own time is what its tags carry, to the millisecond; the same
// clock taken as it is with `timestamp: producer` even when it is 26 years off.
TEST_F(PlantTest, AProducersTimeIsKeptWhenItIsInToleranceOrAskedFor) {
    // A minute of tolerance, so that a loaded machine receiving late does not make it unsynced.
    start(plc_exchange().key("clock_tolerance_ms", "60000").str() +
          ExchangeYaml::consume("old", "10.0.0.8", 3)
              .length(4)
              .timeout_ms(0)
              .key("timestamp", "producer")
              .tag("COUNTER", "0.0", "dint")
              .str());
    const auto now = now_ms();
    send(DatagramBuilder("10.0.0.7", 2, 4)
             .request_id(1)
             .timestamp(static_cast<std::uint32_t>(now / 1000),
                        static_cast<std::uint32_t>(now % 1000) * 1000000 + 123)
             .set("0.0", TagType::dint, 5)
             .build());
    const auto synced = expect_field(topic("plc/COUNTER"), "value", "5");
    EXPECT_EQ(json::parse(synced.payload)["timestamp"], now);
    EXPECT_EQ(wait_status([](const json& s) { return s["accepted"] == 1; })["clock"], "synced");

    send(DatagramBuilder("10.0.0.8", 3, 4)
             .request_id(1)
             .timestamp(clock_2000, 740000000)
             .set("0.0", TagType::dint, 6)
             .build());
    const auto kept = expect_field(topic("old/COUNTER"), "value", "6");
    EXPECT_EQ(json::parse(kept.payload)["timestamp"], std::int64_t{clock_2000} * 1000 + 740);
    const auto status = recorder_->wait_for_message(
        topic("old/_status"), [](const std::string& p) { return json::parse(p)["accepted"] == 1; });
    ASSERT_TRUE(status.has_value());
    EXPECT_EQ(json::parse(status->payload)["clock"], "unsynced");
}

// No timestamp (0/0) is the receive time and clock `none`; and whatever a timestamp says, the
// datagram is never dropped for it: a clock jumping from 2000 to 2106 and back is all accepted.
TEST_F(PlantTest, NoTimestampIsTheReceiveTimeAndNoTimestampEverDropsADatagram) {
    start(plc_exchange().str());
    const auto before = now_ms();
    send(plc_datagram(1, 0, 0, 1));
    const auto value = expect_field(topic("plc/COUNTER"), "value", "1");
    EXPECT_GE(json::parse(value.payload)["timestamp"].get<std::int64_t>(), before);
    EXPECT_EQ(wait_status([](const json& s) { return s["accepted"] == 1; })["clock"], "none");

    send(plc_datagram(2, clock_2000, 0, 2));
    send(plc_datagram(3, 0xFFFFFFFF, 999, 3));  // February 2106, the last second there is
    send(plc_datagram(4, 1, 0, 4));
    send(plc_datagram(5, 0, 0, 5));
    expect_field(topic("plc/COUNTER"), "value", "5");
    const auto status = wait_status([](const json& s) { return s["received"] == 5; });
    EXPECT_EQ(status["accepted"], 5);
    EXPECT_EQ(status["out_of_order"], 0);
    EXPECT_EQ(status["clock"], "none");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
