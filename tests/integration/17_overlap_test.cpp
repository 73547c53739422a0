// Overlapping tags as point lists name them: a status word and its bits, a dint and
// its two halves, at the same bytes. Consumed, each reads its own bits; produced, a write to one
// republishes every tag whose bytes it changed, and one message never sets two of them.

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

std::string exchanges(std::uint16_t capture_port) {
    return ExchangeYaml::consume("plc", "10.0.0.7", 2)
               .length(8)
               .period_ms(100)
               .tag("STATUS", "0.0", "word")
               .tag("RUN", "0.0", "bit")
               .tag("TRIP", "1.7", "bit")
               .tag("TOTAL", "2.0", "dint")
               .tag("TOTAL_LO", "2.0", "int")
               .tag("TOTAL_HI", "4.0", "int")
               .str() +
           ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture_port))
               .period_ms(20)
               .tag("TOTAL", "0.0", "dint", "writable: true")
               .tag("TOTAL_LO", "0.0", "int", "writable: true")
               .tag("TOTAL_HI", "2.0", "int", "writable: true")
               .tag("MODE", "4.0", "word", "writable: true")
               .tag("AUTO", "4.0", "bit", "writable: true")
               .str();
}

class OverlapTest : public GatewayTest {
protected:
    void SetUp() override {
        capture_ = std::make_unique<UdpClient>();
        start(exchanges(capture_->port()));
    }

    /// Publishes a write and returns its result.
    json write(const std::string& topic_suffix, const std::string& payload) {
        const auto from = recorder_->count();
        recorder_->publish(topic(topic_suffix), payload, false);
        const auto result =
            recorder_->wait_for_message(topic(topic_suffix + "/result"), nullptr, 10s, from);
        EXPECT_TRUE(result.has_value()) << "no result for " << topic_suffix;
        return result ? json::parse(result->payload) : json();
    }

    /// A tag of the next datagram the gateway sends (after what it already sent).
    Value produced(const char* address, TagType type) {
        while (capture_->receive(0ms)) {
        }
        const auto bytes = capture_->receive(5s);
        EXPECT_TRUE(bytes.has_value());
        if (!bytes) return Value{false};
        return core::plan::decode_value(std::span(*bytes).subspan(32), type,
                                        core::plan::parse_address(address).value());
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(OverlapTest, CheckNotesEachOverlapInTheByteMap) {
    const auto result = run_command({gateway_binary(), "check", "-c", config_path_}, 10s);
    EXPECT_EQ(result.status, 0) << result.output;
    for (const auto* note : {"note: RUN (0.0, bit) overlaps STATUS (0.0, word)",
                             "note: TRIP (1.7, bit) overlaps STATUS (0.0, word)",
                             "note: TOTAL_LO (2.0, int) overlaps TOTAL (2.0, dint)",
                             "note: TOTAL_HI (4.0, int) overlaps TOTAL (2.0, dint)",
                             "note: AUTO (4.0, bit) overlaps MODE (4.0, word)"}) {
        EXPECT_NE(result.output.find(note), std::string::npos) << note << "\n" << result.output;
    }
}

TEST_F(OverlapTest, ConsumedTagsSharingBytesEachReadTheirOwnBits) {
    send(DatagramBuilder("10.0.0.7", 2, 8)
             .request_id(1)
             .set("0.0", TagType::word, std::uint64_t{0x8001})
             .set("2.0", TagType::dint, std::int64_t{0x00050003})
             .build());
    expect_field(topic("plc/STATUS"), "value", "32769");
    expect_field(topic("plc/RUN"), "value", "true");
    expect_field(topic("plc/TRIP"), "value", "true");
    expect_field(topic("plc/TOTAL"), "value", "327683");
    expect_field(topic("plc/TOTAL_LO"), "value", "3");
    expect_field(topic("plc/TOTAL_HI"), "value", "5");
    // The word clears: its bits follow it.
    const auto from = recorder_->count();
    send(DatagramBuilder("10.0.0.7", 2, 8)
             .request_id(2)
             .set("2.0", TagType::dint, std::int64_t{0x00050003})
             .build());
    expect_field(topic("plc/RUN"), "value", "false", from);
    expect_field(topic("plc/TRIP"), "value", "false", from);
    expect_field(topic("plc/STATUS"), "value", "0", from);
}

TEST_F(OverlapTest, AWriteRepublishesEveryTagWhoseBytesItChanged) {
    EXPECT_EQ(write("sp/TOTAL/set", "327683"), json({{"ok", true}}));  // 0x0005'0003
    expect_field(topic("sp/TOTAL_LO"), "value", "3");
    expect_field(topic("sp/TOTAL_HI"), "value", "5");
    const auto hi_published = recorder_->messages_on(topic("sp/TOTAL_HI")).size();
    auto from = recorder_->count();
    EXPECT_EQ(write("sp/TOTAL_LO/set", "7"), json({{"ok", true}}));
    expect_field(topic("sp/TOTAL"), "value", "327687", from);
    EXPECT_EQ(produced("0.0", TagType::dint), Value{std::int64_t{327687}});
    from = recorder_->count();
    EXPECT_EQ(write("sp/AUTO/set", "true"), json({{"ok", true}}));
    expect_field(topic("sp/MODE"), "value", "1", from);
    // TOTAL_HI did not change, so it was not published again (the echoes of one connection
    // arrive in order: those of the TOTAL_LO write came before MODE's).
    EXPECT_EQ(recorder_->messages_on(topic("sp/TOTAL_HI")).size(), hi_published);
}

TEST_F(OverlapTest, OneMessageSettingTwoOverlappingTagsChangesNothing) {
    EXPECT_EQ(write("sp/TOTAL/set", "1000"), json({{"ok", true}}));
    EXPECT_EQ(write("sp/set", R"({"MODE":2,"TOTAL":1,"TOTAL_HI":2})"),
              json({{"ok", false},
                    {"error",
                     "tags TOTAL and TOTAL_HI share bytes; write them in separate "
                     "messages"}}));
    EXPECT_EQ(produced("0.0", TagType::dint), Value{std::int64_t{1000}});
    EXPECT_EQ(produced("4.0", TagType::word), Value{std::uint64_t{0}});
    const auto metrics = recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& p) {
            return json::parse(p)["writes_rejected"]["overlapping_tags"] == 1;
        },
        10s);
    EXPECT_TRUE(metrics.has_value());
    // Written one at a time, both are applied.
    EXPECT_EQ(write("sp/set", R"({"MODE":2,"TOTAL_HI":2})"), json({{"ok", true}}));
    EXPECT_EQ(produced("0.0", TagType::dint), Value{std::int64_t{0x00020000 + 1000}});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
