// MQTT writes into produced exchanges: applied between productions, answered after the
// datagram carrying them left, rejected with a reason otherwise, and kept across a restart.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
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
               .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
               .tag("START", "4.0", "bit", "writable: true")
               .tag("LEVEL", "5.0", "int", "writable: true")
               .tag("LIMIT", "7.0", "word", "initial: 100")
               .str() +
           ExchangeYaml::consume("plant", "10.9.9.9", 1)
               .length(2)
               .period_ms(100)
               .tag("PV", "0.0", "int")
               .str();
}

Value tag(const std::vector<std::byte>& bytes, const char* address, TagType type) {
    return core::plan::decode_value(std::span(bytes).subspan(32), type,
                                    core::plan::parse_address(address).value());
}

class WriteTest : public GatewayTest {
protected:
    void SetUp() override {
        capture_ = std::make_unique<UdpClient>();
        start(exchanges(capture_->port()));
        // The gateway is producing.
        ASSERT_TRUE(capture_->receive(5s).has_value());
    }

    /// Everything the gateway sent since the last call; the last one is its current image.
    std::vector<std::vector<std::byte>> drain() {
        std::vector<std::vector<std::byte>> all;
        while (auto bytes = capture_->receive(0ms)) all.push_back(std::move(*bytes));
        return all;
    }

    /// The next datagram the gateway sends.
    std::vector<std::byte> next() {
        drain();
        auto bytes = capture_->receive(5s);
        EXPECT_TRUE(bytes.has_value());
        return bytes.value_or(std::vector<std::byte>(64));
    }

    /// Publishes a write and returns the result payload on `result_topic`.
    json write(const std::string& topic_suffix, const std::string& payload, bool retain = false,
               const std::string& result_suffix = "") {
        const auto result_topic =
            topic(result_suffix.empty() ? topic_suffix + "/result" : result_suffix);
        const auto from = recorder_->count();
        recorder_->publish(topic(topic_suffix), payload, retain);
        const auto result = recorder_->wait_for_message(result_topic, nullptr, 10s, from);
        EXPECT_TRUE(result.has_value()) << "no result on " << result_topic;
        return result ? json::parse(result->payload) : json();
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(WriteTest, TagWriteIsCarriedByTheDatagramSentBeforeItsResult) {
    const auto result = write("sp/SPEED_SP/set", "3100.5");
    EXPECT_EQ(result, json({{"ok", true}}));
    // The result is published only after the datagram carrying the write was sent, so that
    // datagram is already in our socket buffer.
    const auto sent = drain();
    ASSERT_FALSE(sent.empty());
    EXPECT_EQ(tag(sent.back(), "0.0", TagType::real), Value{3100.5f});
    // The echo topic reads back the produced value.
    expect_field(topic("sp/SPEED_SP"), "value", "3100.5");
}

TEST_F(WriteTest, JsonObjectFormAndBitsByReadModifyWrite) {
    EXPECT_EQ(write("sp/LEVEL/set", R"({"value":-300})"), json({{"ok", true}}));
    EXPECT_EQ(write("sp/START/set", "true"), json({{"ok", true}}));
    const auto bytes = next();
    EXPECT_EQ(tag(bytes, "5.0", TagType::int_), Value{std::int64_t{-300}});
    EXPECT_EQ(tag(bytes, "4.0", TagType::bit), Value{true});
    EXPECT_EQ(tag(bytes, "0.0", TagType::real), Value{3000.0f});
    EXPECT_EQ(tag(bytes, "7.0", TagType::word), Value{std::uint64_t{100}});
}

TEST_F(WriteTest, MultiTagWriteIsAtomic) {
    EXPECT_EQ(write("sp/set", R"({"SPEED_SP":3200,"START":true})"), json({{"ok", true}}));
    const auto sent = drain();
    ASSERT_FALSE(sent.empty());
    EXPECT_EQ(tag(sent.back(), "0.0", TagType::real), Value{3200.0f});
    EXPECT_EQ(tag(sent.back(), "4.0", TagType::bit), Value{true});
    // No datagram ever carried one of the two without the other.
    for (const auto& bytes : sent) {
        EXPECT_EQ(tag(bytes, "0.0", TagType::real) == Value{3200.0f},
                  tag(bytes, "4.0", TagType::bit) == Value{true});
    }
}

TEST_F(WriteTest, RejectedWritesGiveTheirReasonAndChangeNothing) {
    const auto before = next();
    struct Case {
        std::string topic;
        std::string payload;
        bool retain;
        std::string error_contains;
    };
    const std::vector<Case> cases = {
        {"sp/NOPE/set", "1", false, "unknown tag NOPE"},
        {"sp/LIMIT/set", "1", false, "read-only"},
        {"plant/PV/set", "1", false, "read-only"},
        {"sp/SPEED_SP/set", "4000.5", false, "above max 4000"},
        {"sp/SPEED_SP/set", "-1", false, "below min 0"},
        {"sp/LEVEL/set", "40000", false, "out of range"},
        {"sp/LEVEL/set", "1.5", false, "integer"},
        {"sp/START/set", "\"on\"", false, "string"},
        {"sp/LEVEL/set", "{\"value\":", false, "malformed"},
        {"sp/SPEED_SP/set", "100", true, "retained"},
        {"sp/set", R"({"SPEED_SP":100,"LEVEL":70000})", false, "LEVEL"},
        {"sp/set", R"({"SPEED_SP":100,"NOPE":1})", false, "unknown tag NOPE"},
    };
    for (const auto& c : cases) {
        const auto result = write(c.topic, c.payload, c.retain);
        EXPECT_EQ(result.value("ok", true), false) << c.topic << " " << c.payload;
        EXPECT_NE(result.value("error", std::string()).find(c.error_contains), std::string::npos)
            << c.topic << " " << c.payload << " -> " << result.dump();
    }
    const auto after = next();
    EXPECT_TRUE(std::equal(before.begin() + 32, before.end(), after.begin() + 32))
        << "rejected writes changed the produced data";
}

TEST_F(WriteTest, Mqtt5ResponseTopicAndCorrelationData) {
    const auto from = recorder_->count();
    // A client's own topic, outside the base topic (the gateway refuses to answer on its own).
    recorder_->publish_request(topic("sp/SPEED_SP/set"), "1234", "replies/ui", "req-42");
    const auto reply = recorder_->wait_for_message("replies/ui", nullptr, 10s, from);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(json::parse(reply->payload), json({{"ok", true}}));
    EXPECT_EQ(reply->correlation_data, "req-42");
}

TEST_F(WriteTest, RestartProducesTheLastWrittenValues) {
    EXPECT_EQ(write("sp/set", R"({"SPEED_SP":2500,"LEVEL":-7})"), json({{"ok", true}}));
    gateway_->signal(SIGKILL);
    gateway_->wait(5s);
    drain();
    start_gateway();
    // The very first datagram after the restart carries the written values.
    const auto first = capture_->receive(5s);
    ASSERT_TRUE(first.has_value());
    EXPECT_EQ(tag(*first, "0.0", TagType::real), Value{2500.0f});
    EXPECT_EQ(tag(*first, "5.0", TagType::int_), Value{std::int64_t{-7}});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
