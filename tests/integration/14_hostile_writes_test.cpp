// Writes from a client that means harm or is careless: none may disconnect the
// gateway, make it publish on its own topics, or slip a wrong value into a datagram.

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

std::string exchanges(std::uint16_t capture_port) {
    return ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture_port))
        .period_ms(20)
        .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 3000")
        .tag("TOTAL", "4.0", "lint", "writable: true")
        .str();
}

class HostileWriteTest : public GatewayTest {
protected:
    void start_with(const std::string& mqtt_extra = "") {
        capture_ = std::make_unique<UdpClient>();
        start(exchanges(capture_->port()), mqtt_extra);
        ASSERT_TRUE(capture_->receive(5s).has_value());  // producing
    }

    /// Publishes an MQTT 5 request and returns the result that arrives on `answered_on`.
    json request(const std::string& set_suffix, const std::string& payload,
                 const std::string& response_topic, const std::string& answered_on) {
        const auto from = recorder_->count();
        recorder_->publish_request(topic(set_suffix), payload, response_topic, "corr-7");
        const auto result = recorder_->wait_for_message(answered_on, nullptr, 10s, from);
        EXPECT_TRUE(result.has_value()) << "no result on " << answered_on;
        if (!result) return json();
        EXPECT_EQ(result->correlation_data, "corr-7");
        return json::parse(result->payload);
    }

    json write(const std::string& set_suffix, const std::string& payload) {
        const auto from = recorder_->count();
        recorder_->publish(topic(set_suffix), payload);
        const auto result =
            recorder_->wait_for_message(topic(set_suffix + "/result"), nullptr, 10s, from);
        EXPECT_TRUE(result.has_value()) << "no result for " << set_suffix;
        return result ? json::parse(result->payload) : json();
    }

    std::size_t onlines() const {
        std::size_t n = 0;
        for (const auto& m : recorder_->messages_on(availability_topic())) {
            n += m.payload == "online";
        }
        return n;
    }

    /// The value of the lint tag in the next datagram the gateway sends.
    Value next_total() {
        while (capture_->receive(0ms)) {
        }
        const auto bytes = capture_->receive(5s);
        EXPECT_TRUE(bytes.has_value());
        if (!bytes) return Value{false};
        return core::plan::decode_value(std::span(*bytes).subspan(32), TagType::lint, {4, 0});
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(HostileWriteTest, AWildcardResponseTopicIsRefusedAndTheGatewayStaysConnected) {
    start_with();
    const auto result_topic = topic("sp/SPEED_SP/set/result");
    for (const auto* bad : {"rt/#", "a/+/b"}) {
        EXPECT_EQ(request("sp/SPEED_SP/set", "1234", bad, result_topic),
                  json({{"ok", false}, {"error", "bad response topic"}}))
            << bad;
    }
    // Still connected: the next write is answered, on the same connection.
    EXPECT_EQ(write("sp/SPEED_SP/set", "1500"), json({{"ok", true}}));
    EXPECT_EQ(onlines(), 1u);
    const auto metrics = recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& payload) {
            return json::parse(payload)["writes_rejected"]["bad_response_topic"] == 2;
        },
        10s);
    ASSERT_TRUE(metrics.has_value());
    EXPECT_EQ(json::parse(metrics->payload)["writes_rejected"]["bad_response_topic"], 2);
}

TEST_F(HostileWriteTest, AResponseTopicAmongTheGatewaysOwnTopicsIsRefused) {
    start_with();
    const auto result_topic = topic("sp/TOTAL/set/result");
    for (const auto& own : {availability_topic(), topic("sp/SPEED_SP"), topic("sp/_status")}) {
        EXPECT_EQ(request("sp/TOTAL/set", "5", own, result_topic),
                  json({{"ok", false}, {"error", "bad response topic"}}))
            << own;
    }
    for (const auto& own : {availability_topic(), topic("sp/SPEED_SP"), topic("sp/_status")}) {
        for (const auto& m : recorder_->messages_on(own)) {
            EXPECT_EQ(m.payload.find("\"ok\""), std::string::npos) << own << ": " << m.payload;
        }
    }
    EXPECT_EQ(recorder_->last(availability_topic())->payload, "online");
    // Below a set topic the gateway publishes only results: a client may ask for its own there.
    EXPECT_EQ(
        request("sp/TOTAL/set", "6", topic("sp/TOTAL/set/hmi-3"), topic("sp/TOTAL/set/hmi-3")),
        json({{"ok", true}}));
}

TEST_F(HostileWriteTest, ResponseTopicsUnderTheBaseCanBeAllowed) {
    start_with("  allow_response_topics_under_base: true\n");
    EXPECT_EQ(request("sp/TOTAL/set", "5", topic("replies/hmi"), topic("replies/hmi")),
              json({{"ok", true}}));
}

TEST_F(HostileWriteTest, LintWritesAreExact) {
    start_with();
    EXPECT_EQ(write("sp/TOTAL/set", "9007199254740993.0"), json({{"ok", true}}));
    EXPECT_EQ(next_total(), Value{std::int64_t{9007199254740993}});
    for (const auto* bad : {"-9223372036854775809", "9223372036854775808"}) {
        const auto result = write("sp/TOTAL/set", bad);
        EXPECT_EQ(result["error"],
                  "out of range for lint (-9223372036854775808..9223372036854775807)")
            << bad;
    }
    EXPECT_EQ(write("sp/TOTAL/set", "9007199254740992.5"),
              json({{"ok", false}, {"error", "expected an integer"}}));
    EXPECT_EQ(write("sp/TOTAL/set", "-9223372036854775808"), json({{"ok", true}}));
    EXPECT_EQ(next_total(), Value{std::numeric_limits<std::int64_t>::min()});
}

TEST_F(HostileWriteTest, APayloadOverTheLimitSaysSo) {
    start_with();
    EXPECT_EQ(write("sp/TOTAL/set", std::string(300 * 1024, ' ') + "1"),
              json({{"ok", false}, {"error", "payload too large (307201 bytes, limit 262144)"}}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
