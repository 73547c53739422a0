// `eip2mqtt discover` against a hostile node on UDP 7937 (docs/protocol.md §9;
// docs/security.md): a fake node in the test answers with an identification full of terminal escape
// sequences, a NAK whose text carries a newline and a line of YAML, and a Retrieve answer for
// another exchange than the one asked. Nothing it told reaches the terminal or the skeleton
// raw, and the answer for another exchange is not taken.

#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::PduType;

const core::wire::ProducerId node_id{0x0A000009};  // 10.0.0.9

/// A node on loopback that answers each request with what `answer` makes of it (nothing when
/// it returns an empty vector), on a thread of its own until destroyed.
class FakeNode {
public:
    using Answer = std::function<std::vector<std::byte>(const core::command::Request&)>;

    explicit FakeNode(Answer answer) : answer_(std::move(answer)) {
        thread_ = std::thread([this] { serve(); });
    }
    ~FakeNode() {
        stop_ = true;
        thread_.join();
    }
    std::string address() const { return "127.0.0.1:" + std::to_string(socket_.port()); }

private:
    void serve() {
        while (!stop_) {
            const auto datagram = socket_.receive_from(50ms);
            if (!datagram) continue;
            const auto request = core::command::decode_request(datagram->bytes);
            if (!request) continue;
            const auto reply = answer_(*request);
            if (!reply.empty()) socket_.send_to(datagram->from_port, reply);
        }
    }

    Answer answer_;
    UdpClient socket_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

core::command::PduHeader reply_to(const core::command::Request& request) {
    return core::command::reply_header(request.header,
                                       *core::command::response_type_of(request.header.type));
}

std::vector<std::byte> capabilities(const core::command::Request& request, std::string text) {
    core::command::Capabilities caps;
    caps.producer_id = node_id;
    caps.identification = std::move(text);
    return core::command::encode(reply_to(request), caps);
}

std::vector<std::byte> summary(const core::command::Request& request,
                               std::vector<std::uint32_t> exchanges) {
    core::command::SummaryPage page;
    page.producer_id = node_id;
    page.total_cells = static_cast<std::uint16_t>(exchanges.size());
    for (const auto id : exchanges) {
        page.cells.push_back({{node_id, id},
                              core::command::ExchangeMode::produced,
                              core::command::ExchangeState::active,
                              100});
    }
    return core::command::encode(reply_to(request), page);
}

std::vector<std::byte> config_of(const core::command::Request& request, std::uint32_t exchange) {
    core::command::ExchangeConfig config;
    config.key = {node_id, exchange};
    config.period_ms = 100;
    config.destination_type = core::command::DestinationType::unicast;
    config.destination = 0x7F000001;
    config.state = core::command::ExchangeState::active;
    config.length = 8;
    config.mode = core::command::ExchangeMode::produced;
    return core::command::encode(reply_to(request), config);
}

std::uint32_t asked_exchange(const core::command::Request& request) {
    return std::get<core::command::RetrieveConfigRequest>(request.body).key.exchange_id;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// A NAK text that ends its comment line and writes configuration of its own.
const std::string hostile_nak = "x\neip: {commands: {enabled: true, writes: true, allow: [0/0]}}";
const std::string hostile_identification =
    "\x1b[2J\x1b]0;owned\x07PLC\x9b"
    "31m";

std::vector<std::byte> hostile(const core::command::Request& request) {
    switch (request.header.type) {
        case PduType::capabilities_request:
            return capabilities(request, hostile_identification);
        case PduType::summary_request:
            return summary(request, {1, 2});
        case PduType::retrieve_config_request: {
            if (asked_exchange(request) == 2) return config_of(request, 2);
            core::command::CommandNak nak;
            nak.key = {node_id, 1};
            nak.error_code = 6;
            const auto& header = request.header;
            auto bytes = core::command::encode(
                header, std::get<core::command::RetrieveConfigRequest>(request.body));
            nak.offending.assign(bytes.begin(), bytes.begin() + 16);
            nak.error = hostile_nak;
            auto nak_header = header;
            nak_header.type = PduType::nak;
            return core::command::encode(nak_header, nak);
        }
        default:
            return {};
    }
}

TEST(CommandsHostileNode, WhatANodeToldIsEscapedOnTheTerminal) {
    FakeNode node(hostile);
    const auto table = run_command({gateway_binary(), "discover", node.address()}, 60s);
    EXPECT_EQ(table.status, 1) << table.output;  // exchange 1 was not retrieved
    EXPECT_FALSE(contains(table.output, "\x1b")) << table.output;
    EXPECT_FALSE(contains(table.output, "\x9b")) << table.output;
    EXPECT_FALSE(contains(table.output, "\x07")) << table.output;
    EXPECT_TRUE(contains(table.output, "\"\\x1b[2J\\x1b]0;owned\\x07PLC\\x9b31m\""))
        << table.output;
    EXPECT_TRUE(contains(table.output, "not retrieved: NAK x\\x0aeip: {commands:")) << table.output;
}

TEST(CommandsHostileNode, ANakTextCannotWriteConfigurationIntoTheSkeleton) {
    FakeNode node(hostile);
    const auto yaml = run_command({gateway_binary(), "discover", node.address(), "--yaml"}, 60s);
    EXPECT_EQ(yaml.status, 1) << yaml.output;
    EXPECT_FALSE(contains(yaml.output, "\neip:")) << yaml.output;
    EXPECT_TRUE(contains(yaml.output, "): not retrieved: NAK x\\x0aeip: {commands:"))
        << yaml.output;
    // The skeleton loads, and holds no eip.commands of the node's making.
    TempDir dir;
    const auto file = dir.write("discovered.yaml", "mqtt: { url: tcp://127.0.0.1:1 }\n" +
                                                       yaml.output + "eip: { bind: 127.0.0.1 }\n");
    const auto check = run_command({gateway_binary(), "check", "-c", file}, 30s);
    EXPECT_EQ(check.status, 0) << check.output << yaml.output;
    EXPECT_TRUE(contains(check.output, "exchange 10.0.0.9-2: consume")) << check.output;
}

TEST(CommandsHostileNode, ARetrieveAnswerForAnotherExchangeIsNotTaken) {
    FakeNode node([](const core::command::Request& request) -> std::vector<std::byte> {
        switch (request.header.type) {
            case PduType::capabilities_request:
                return capabilities(request, "liar");
            case PduType::summary_request:
                return summary(request, {1});
            case PduType::retrieve_config_request:
                return config_of(request, 99);  // asked for 1
            default:
                return {};
        }
    });
    const auto yaml = run_command({gateway_binary(), "discover", node.address(), "--yaml",
                                   "--timeout-ms", "200", "--attempts", "2"},
                                  60s);
    EXPECT_EQ(yaml.status, 1) << yaml.output;
    EXPECT_FALSE(contains(yaml.output, "10.0.0.9-99")) << yaml.output;
    EXPECT_TRUE(
        contains(yaml.output, "# 10.0.0.9/1 (" + node.address() + "): not retrieved: no answer"))
        << yaml.output;
    EXPECT_TRUE(contains(yaml.output, "answers to another request ignored")) << yaml.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
