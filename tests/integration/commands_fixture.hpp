#pragma once
/// What the tests of the gateway's responder on UDP 7937 share: the port it answers on, a
/// socket that receives what it produces, Read cells of its produced exchange, and its
/// `commands` metrics.

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eip2mqtt/core/command/data_pdus.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {

/// A requester address of the loopback network other than the tests' own 127.0.0.1.
inline constexpr std::uint32_t other_source = 0x7F000002;  // 127.0.0.2
/// The produced exchange the tests read and write: 10.1.2.3, exchange 10.
inline const core::wire::ExchangeKey produced_key{core::wire::ProducerId{0x0A010203}, 10};

class CommandsFixture : public GatewayTest {
protected:
    /// Options that enable the responder on a free port; `commands` adds keys to eip.commands.
    /// Also opens the socket that receives the produced datagrams.
    GatewayOptions commands_options(const std::string& commands) {
        capture_ = std::make_unique<UdpClient>();
        commands_port_ = free_udp_port();
        GatewayOptions options;
        options.eip_extra = "  commands: { enabled: true, port: " + std::to_string(commands_port_) +
                            commands + " }\n";
        return options;
    }

    core::command::DataPdu cells(std::vector<core::command::Cell> list) const {
        core::command::DataPdu pdu;
        pdu.key = produced_key;
        pdu.cells = std::move(list);
        return pdu;
    }

    /// The next metrics message whose `commands` satisfies `done`.
    nlohmann::json commands_metrics(const std::function<bool(const nlohmann::json&)>& done) {
        using namespace std::chrono_literals;
        const auto message = recorder_->wait_for_message(
            metrics_topic(),
            [&](const std::string& payload) {
                const auto metrics = nlohmann::json::parse(payload, nullptr, false);
                return metrics.contains("commands") && done(metrics);
            },
            20s);
        EXPECT_TRUE(message.has_value()) << "no such metrics";
        return message ? nlohmann::json::parse(message->payload) : nlohmann::json();
    }

    std::unique_ptr<UdpClient> capture_;
    std::uint16_t commands_port_ = 0;
};

}  // namespace eip2mqtt::test
