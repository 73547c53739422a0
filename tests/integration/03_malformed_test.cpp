// Malformed datagrams never crash or stall the gateway; each is counted by reason.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .timeout_ms(0)
                                     .tag("SPEED", "0.0", "dint")
                                     .str();

std::vector<std::byte> valid(std::uint16_t rid, std::int64_t value) {
    return DatagramBuilder("10.0.0.2", 7, 4)
        .request_id(rid)
        .set("0.0", TagType::dint, value)
        .build();
}

class MalformedTest : public GatewayTest {};

TEST_F(MalformedTest, EveryMalformedDatagramIsCountedByReasonAndTheGatewayGoesOn) {
    start(one_exchange);
    send(valid(1, 10));
    expect_field(topic("pump/SPEED"), "value", "10");

    auto short_one = valid(2, 11);
    short_one.resize(31);
    auto wrong_type = valid(2, 11);
    wrong_type[0] = std::byte{0x01};
    wrong_type[1] = std::byte{0x0D};
    auto header_only = valid(2, 11);
    header_only.resize(32);
    const auto unknown = DatagramBuilder("10.0.0.2", 124, 4).request_id(2).build();
    auto oversized = valid(2, 11);
    oversized.resize(2000);
    send(short_one);
    send(wrong_type);
    send(header_only);
    send(unknown);
    send(oversized);
    send({});

    // Still consuming afterwards.
    send(valid(2, 12));
    expect_field(topic("pump/SPEED"), "value", "12");

    const auto metrics = recorder_->wait_for_message(
        metrics_topic(), [](const std::string& p) { return json::parse(p)["accepted"] == 2; });
    ASSERT_TRUE(metrics.has_value());
    const auto dropped = json::parse(metrics->payload)["dropped"];
    EXPECT_EQ(dropped["too_short"], 2);  // 31 bytes and an empty datagram
    EXPECT_EQ(dropped["not_data_pdu"], 1);
    EXPECT_EQ(dropped["no_data"], 1);
    EXPECT_EQ(dropped["unknown_exchange"], 1);
    EXPECT_EQ(dropped["too_long"], 1);
    EXPECT_TRUE(gateway_->running());
}

TEST_F(MalformedTest, LengthMismatchIsCountedAndNotConsumed) {
    start(one_exchange);
    send(valid(1, 10));
    expect_field(topic("pump/SPEED"), "value", "10");
    auto longer =
        DatagramBuilder("10.0.0.2", 7, 5).request_id(2).set("0.0", TagType::dint, std::int64_t{99});
    send(longer.build());
    expect_field(topic("pump/_status"), "state", "\"length_mismatch\"");
    const auto metrics = recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return json::parse(p)["dropped"]["length_mismatch"] == 1;
    });
    EXPECT_TRUE(metrics.has_value());
    for (const auto& m : recorder_->messages_on(topic("pump/SPEED"))) {
        EXPECT_NE(json::parse(m.payload)["value"], 99);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
