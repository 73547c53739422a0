// Anti-spoofing `source` on consumed exchanges, and per-tag write rate limits.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

class SourceAndRateLimitTest : public GatewayTest {};

TEST_F(SourceAndRateLimitTest, DatagramsFromAnotherSourceAreDroppedAndCounted) {
    start(ExchangeYaml::consume("trusted", "10.0.0.1", 1)
              .length(4)
              .period_ms(1000)
              .key("source", "127.0.0.1")
              .tag("A", "0.0", "dint")
              .str() +
          ExchangeYaml::consume("spoofed", "10.0.0.1", 2)
              .length(4)
              .period_ms(1000)
              .key("source", "10.0.0.1")
              .tag("A", "0.0", "dint")
              .str());
    // The test sends from 127.0.0.1: right for `trusted`, wrong for `spoofed`.
    send(DatagramBuilder("10.0.0.1", 2, 4)
             .request_id(1)
             .set("0.0", TagType::dint, std::int64_t{666})
             .build());
    send(DatagramBuilder("10.0.0.1", 1, 4)
             .request_id(1)
             .set("0.0", TagType::dint, std::int64_t{7})
             .build());
    expect_field(topic("trusted/A"), "value", "7");
    const auto metrics = recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return json::parse(p)["dropped"]["wrong_source"] == 1;
    });
    EXPECT_TRUE(metrics.has_value());
    EXPECT_TRUE(recorder_->messages_on(topic("spoofed/A")).empty());
}

TEST_F(SourceAndRateLimitTest, WritesBeyondTheTagRateAreRejected) {
    UdpClient capture;
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture.port()))
              .period_ms(20)
              .tag("SP", "0.0", "dint", "writable: true, max_writes_per_s: 0.001")
              .str());
    // A burst of one write is allowed; the next within 1,000 s is refused with its reason.
    std::vector<json> results;
    for (int i = 1; i <= 2; ++i) {
        const auto from = recorder_->count();
        recorder_->publish(topic("sp/SP/set"), std::to_string(i));
        const auto result =
            recorder_->wait_for_message(topic("sp/SP/set/result"), nullptr, 10s, from);
        ASSERT_TRUE(result.has_value());
        results.push_back(json::parse(result->payload));
    }
    EXPECT_EQ(results[0], json({{"ok", true}}));
    EXPECT_EQ(results[1].value("ok", true), false);
    EXPECT_NE(results[1].value("error", std::string()).find("writes per second"), std::string::npos)
        << results[1].dump();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
