// The gateway's responder on UDP 7937 against reflection, amplification and forged sources
// (docs/protocol.md §9.7; docs/security.md), with the real binary: a requester that has not
// proved its address gets no more bytes than it sent and writes nothing; one flooding source
// does not starve another; a response with a bad version gets no NAK; `allow: []` answers
// nobody; a write the value checks refuse is counted by its reason.

#include <nlohmann/json.hpp>
#include <string>

#include "eip2mqtt/core/command/address_proof.hpp"
#include "eip2mqtt/core/command/command_status.hpp"
#include "tests/integration/commands_fixture.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/command_client.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::CommandStatus;
using core::command::PduType;
using nlohmann::json;

class CommandsProofTest : public CommandsFixture {
protected:
    /// Starts the gateway with three exchanges and its responder; `commands` adds keys to
    /// eip.commands.
    void start_with(const std::string& commands) {
        auto options = commands_options(commands);
        const auto to = "127.0.0.1:" + std::to_string(capture_->port());
        start(ExchangeYaml::produce("sp", "10.1.2.3", 10, to)
                      .period_ms(50)
                      .tag("SPEED_SP", "0.0", "word", "writable: true, max: 4000, initial: 3000")
                      .str() +
                  ExchangeYaml::produce("sp2", "10.1.2.3", 11, to).period_ms(1000).length(4).str() +
                  ExchangeYaml::produce("sp3", "10.1.2.3", 12, to).period_ms(1000).length(4).str(),
              "", options);
    }

    std::uint64_t read_speed(CommandClient& client) {
        const auto response = client.ask(commands_port_, PduType::read_request, cells({{0, 2}}));
        EXPECT_TRUE(response.has_value());
        if (!response || response->header.status != 0) return 0;
        const auto& data = std::get<core::command::DataPdu>(response->body).cells.at(0).data;
        return std::to_integer<std::uint64_t>(data[0]) | std::to_integer<std::uint64_t>(data[1])
                                                             << 8;
    }
};

TEST_F(CommandsProofTest, ASummaryFromAnUnprovenSourceBringsBackNoMoreThanItsSize) {
    start_with("");
    CommandClient client;
    const auto request = client.request(PduType::summary_request, core::command::SummaryRequest{0});
    client.udp().send_to(commands_port_, request);
    const auto answer = client.udp().receive(5s);
    ASSERT_TRUE(answer.has_value());
    EXPECT_LE(answer->size(), request.size());
    EXPECT_TRUE(core::command::challenge_token(*answer).has_value());
    // Carrying the token, the whole Summary: three exchanges.
    const auto response =
        client.ask(commands_port_, PduType::summary_request, core::command::SummaryRequest{0});
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, 0);
    EXPECT_EQ(std::get<core::command::SummaryPage>(response->body).cells.size(), 3u);
}

TEST_F(CommandsProofTest, AForgedWriteFromAnAllowedAddressIsNotApplied) {
    start_with(", writes: true");
    // 127.0.0.2 is allowed (127.0.0.0/8), and its datagrams could come from anyone: without
    // the token of 127.0.0.2, the write is answered with a challenge and not applied.
    CommandClient forger(other_source);
    forger.udp().send_to(commands_port_,
                         forger.request(PduType::write_request,
                                        cells({{0, 2, {std::byte{0xD2}, std::byte{0x04}}, {}}})));
    CommandClient reader;
    EXPECT_EQ(read_speed(reader), 3000u);
    const auto challenge = forger.udp().receive(5s);
    ASSERT_TRUE(challenge.has_value());
    const auto header = core::command::decode_header(*challenge);
    ASSERT_TRUE(header.ok());
    EXPECT_EQ(header->status, static_cast<std::uint8_t>(CommandStatus::prove_address));
    const auto metrics =
        commands_metrics([](const json& m) { return m["commands"]["challenged"].get<int>() >= 2; });
    EXPECT_EQ(metrics["writes_by_origin"]["commands"], 0);
}

TEST_F(CommandsProofTest, OneFloodingSourceDoesNotStarveAnother) {
    start_with(", max_requests_per_s: 100, max_requests_per_s_per_source: 5");
    CommandClient flooder(other_source);
    flooder.ask(commands_port_, PduType::capabilities_request,
                core::command::CapabilitiesRequest{});  // proves 127.0.0.2
    for (int i = 0; i < 150; ++i) {
        flooder.udp().send_to(commands_port_, flooder.request(PduType::summary_request,
                                                              core::command::SummaryRequest{0}));
    }
    CommandClient client;
    const auto response =
        client.ask(commands_port_, PduType::summary_request, core::command::SummaryRequest{0});
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, 0);
    commands_metrics(
        [](const json& m) { return m["commands"]["dropped_per_source"].get<int>() >= 140; });
}

TEST_F(CommandsProofTest, AResponseWithABadVersionGetsNoNak) {
    start_with(", trusted: [ 127.0.0.1/32 ]");
    CommandClient client;
    core::command::ExchangeConfig config;
    config.key = produced_key;
    core::command::PduHeader header;
    header.type = PduType::retrieve_config_response;
    header.request_id = 500;
    auto response = core::command::encode(header, config);
    response[4] = std::byte{2};
    client.udp().send_to(commands_port_, response);
    client.udp().send_to(commands_port_, client.request(PduType::capabilities_request,
                                                        core::command::CapabilitiesRequest{}));
    // Handled in order: the first datagram back is the answer to the request, no NAK.
    const auto first = client.udp().receive(5s);
    ASSERT_TRUE(first.has_value());
    EXPECT_EQ(core::command::decode_header(*first)->type, PduType::capabilities_response);
    const auto metrics = commands_metrics(
        [](const json& m) { return m["commands"]["requests"]["capabilities"] == 1; });
    EXPECT_EQ(metrics["commands"]["naks"]["wrong_version"], 0);
    EXPECT_EQ(metrics["commands"]["ignored"], 1);
}

TEST_F(CommandsProofTest, AllowWrittenEmptyAnswersNobodyAndCheckSaysSo) {
    start_with(", allow: []");
    CommandClient client;
    EXPECT_FALSE(client
                     .ask(commands_port_,
                          client.request(PduType::capabilities_request,
                                         core::command::CapabilitiesRequest{}),
                          500ms)
                     .has_value());
    commands_metrics([](const json& m) { return m["commands"]["refused"] == 1; });
    const auto check = run_command({gateway_binary(), "check", "-c", config_path_}, 30s);
    EXPECT_EQ(check.status, 0) << check.output;
    EXPECT_NE(check.output.find(": warning: eip.commands.allow is empty: the command port answers "
                                "nobody"),
              std::string::npos)
        << check.output;
}

TEST_F(CommandsProofTest, AWriteTheValueChecksRefuseIsCountedByItsReason) {
    start_with(", writes: true");
    CommandClient client;
    // 5000 (88 13) is over SPEED_SP's max of 4000.
    const auto response = client.ask(commands_port_, PduType::write_request,
                                     cells({{0, 2, {std::byte{0x88}, std::byte{0x13}}, {}}}));
    ASSERT_TRUE(response.has_value());
    EXPECT_EQ(response->header.status, static_cast<std::uint8_t>(CommandStatus::rejected));
    const auto metrics =
        commands_metrics([](const json& m) { return m["writes_rejected"]["above_max"] == 1; });
    EXPECT_EQ(metrics["writes_by_origin"]["commands"], 0);
    EXPECT_EQ(read_speed(client), 3000u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
