// The gateway's responder on UDP 7937 (docs/protocol.md §9, docs/commissioning.md) with the
// real binary: a Read returns what an MQTT write put in a produced exchange; a Write is refused
// with writes off and changes nothing, and with writes on is applied, sent, echoed on MQTT and
// answered after its datagram left; a source outside `allow` gets nothing; a flood over the
// rate limit is bounded and counted.

#include <nlohmann/json.hpp>
#include <string>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/integration/commands_fixture.hpp"
#include "tests/support/command_client.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::CommandStatus;
using core::command::PduType;
using nlohmann::json;

class CommandsTest : public CommandsFixture {
protected:
    /// Starts the gateway with its responder; `commands` adds keys to eip.commands.
    void start_with(const std::string& commands) {
        auto options = commands_options(commands);
        start(ExchangeYaml::produce("sp", "10.1.2.3", 10,
                                    "127.0.0.1:" + std::to_string(capture_->port()))
                  .period_ms(20)
                  .tag("SPEED_SP", "0.0", "word", "writable: true, max: 4000, initial: 3000")
                  .tag("MODE", "2.0", "byte", "initial: 7")
                  .str(),
              "", options);
        ASSERT_TRUE(capture_->receive(5s).has_value());  // producing
    }

    /// Drains the datagrams the gateway produced so far; the value of SPEED_SP in each.
    std::vector<std::uint64_t> produced_speeds() {
        std::vector<std::uint64_t> speeds;
        while (auto bytes = capture_->receive(0ms)) {
            speeds.push_back(std::get<std::uint64_t>(core::plan::decode_value(
                std::span(*bytes).subspan(32), core::plan::TagType::word, {0, 0})));
        }
        return speeds;
    }

    /// SPEED_SP as a Read of 2 bytes at offset 0 returns it.
    std::uint64_t read_speed(CommandClient& client) {
        const auto response = client.ask(commands_port_, PduType::read_request, cells({{0, 2}}));
        EXPECT_TRUE(response.has_value());
        if (!response) return 0;
        EXPECT_EQ(response->header.status, 0);
        const auto& data = std::get<core::command::DataPdu>(response->body).cells.at(0).data;
        return std::to_integer<std::uint64_t>(data[0]) | std::to_integer<std::uint64_t>(data[1])
                                                             << 8;
    }
};

TEST_F(CommandsTest, AReadReturnsWhatAnMqttWritePutInAProducedExchange) {
    start_with("");
    CommandClient client;
    EXPECT_EQ(read_speed(client), 3000u);  // the initial value
    const auto from = recorder_->count();
    recorder_->publish(topic("sp/SPEED_SP/set"), "1234");
    const auto result =
        recorder_->wait_for_message(topic("sp/SPEED_SP/set/result"), nullptr, 10s, from);
    ASSERT_TRUE(result.has_value());
    EXPECT_EQ(json::parse(result->payload)["ok"], true);
    EXPECT_EQ(read_speed(client), 1234u);
}

TEST_F(CommandsTest, WithWritesOffAWriteIsRefusedAndChangesNothing) {
    start_with("");
    CommandClient client;
    const auto response = client.ask(commands_port_, PduType::write_request,
                                     cells({{0, 2, {std::byte{0xD2}, std::byte{0x04}}, {}}}));
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.type, PduType::write_response);
    EXPECT_EQ(response->header.status, static_cast<std::uint8_t>(CommandStatus::not_permitted));
    // Nothing changed: the image, what is produced, and no write was counted.
    EXPECT_EQ(read_speed(client), 3000u);
    produced_speeds();
    ASSERT_TRUE(capture_->receive(5s).has_value());
    for (const auto speed : produced_speeds()) EXPECT_EQ(speed, 3000u);
    const auto metrics = commands_metrics([](const json& m) {
        return m["commands"]["requests"]["write"] == 1 && m["commands"]["requests"]["read"] == 1;
    });
    EXPECT_EQ(metrics["writes_by_origin"]["commands"], 0);
    EXPECT_EQ(metrics["commands"]["errors"], 1);
}

TEST_F(CommandsTest, WithWritesOnAWriteIsAppliedEchoedAndAnsweredAfterItsDatagram) {
    start_with(", writes: true");
    CommandClient client;
    const auto from = recorder_->count();
    produced_speeds();
    const auto response = client.ask(commands_port_, PduType::write_request,
                                     cells({{0, 2, {std::byte{0xD2}, std::byte{0x04}}, {}}}));
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, 0);
    // Answered after the send: a datagram carrying 1234 was already delivered to the consumer
    // (loopback delivers within the send) when the response came.
    const auto speeds = produced_speeds();
    EXPECT_NE(std::find(speeds.begin(), speeds.end(), 1234u), speeds.end());
    EXPECT_EQ(read_speed(client), 1234u);
    expect_field(topic("sp/SPEED_SP"), "value", "1234", from);
    const auto metrics =
        commands_metrics([](const json& m) { return m["writes_by_origin"]["commands"] == 1; });
    EXPECT_EQ(metrics["writes_by_origin"]["mqtt"], 0);
    EXPECT_EQ(schema_problem(schema_file("metrics.json"), metrics.dump()), "");
    // A write outside the writable tag (MODE is read-only) is refused whole.
    const auto refused =
        client.ask(commands_port_, PduType::write_request,
                   cells({{0, 3, {std::byte{1}, std::byte{0}, std::byte{9}}, {}}}));
    ASSERT_TRUE(refused.has_value());
    EXPECT_EQ(refused->header.status, static_cast<std::uint8_t>(CommandStatus::not_permitted));
    EXPECT_EQ(read_speed(client), 1234u);
}

TEST_F(CommandsTest, ASourceOutsideAllowGetsNothing) {
    start_with(", allow: [ 127.0.0.1/32 ]");
    CommandClient stranger(other_source);
    CommandClient allowed;
    stranger.udp().send_to(commands_port_, stranger.request(PduType::capabilities_request,
                                                            core::command::CapabilitiesRequest{}));
    // The allowed requester's answer comes after the stranger's datagram was handled: the
    // responder reads its socket in order.
    ASSERT_TRUE(allowed
                    .ask(commands_port_, PduType::capabilities_request,
                         core::command::CapabilitiesRequest{})
                    .has_value());
    EXPECT_FALSE(stranger.udp().receive(0ms).has_value());
    commands_metrics([](const json& m) {
        return m["commands"]["refused"] == 1 && m["commands"]["requests"]["capabilities"] == 1;
    });
}

TEST_F(CommandsTest, AFloodOverTheRateLimitIsBoundedAndCounted) {
    // Trusted: answered in full without proving its address, so that every answer counts.
    start_with(", max_requests_per_s: 10, trusted: [ 127.0.0.1/32 ]");
    CommandClient flooder;
    constexpr int sent = 200;  // within a socket's default receive buffer
    const auto started = std::chrono::steady_clock::now();
    for (int i = 0; i < sent; ++i) {
        flooder.udp().send_to(
            commands_port_,
            flooder.request(PduType::capabilities_request, core::command::CapabilitiesRequest{}));
    }
    const auto metrics = commands_metrics([&](const json& m) {
        return m["commands"]["requests"]["capabilities"].get<int>() +
                   m["commands"]["dropped"].get<int>() ==
               sent;
    });
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const int answered = metrics["commands"]["requests"]["capabilities"];
    // A second's worth at once, then 10 a second: never more, however slow the machine (every
    // answer counted was given inside [started, now], so load only widens the bound).
    EXPECT_LE(answered, 10 + static_cast<int>(10 * elapsed_s) + 1) << elapsed_s << " s";
    EXPECT_GE(metrics["commands"]["dropped"].get<int>(), sent - answered);
    int responses = 0;
    while (flooder.udp().receive(0ms)) ++responses;
    EXPECT_EQ(responses, answered);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
