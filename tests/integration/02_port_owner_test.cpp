// The gateway owns its UDP port: a second gateway on the same port is refused at start with a
// message that names the first, which goes on undisturbed (no datagram taken from it, no MQTT
// session fought over).

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .timeout_ms(0)
                                     .tag("SPEED", "0.0", "real")
                                     .str();

std::vector<std::byte> speed(std::uint16_t rid, float value) {
    return DatagramBuilder("10.0.0.2", 7, 4)
        .request_id(rid)
        .set("0.0", TagType::real, value)
        .build();
}

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

class PortOwnerTest : public GatewayTest {};

TEST_F(PortOwnerTest, ASecondGatewayOnThePortIsRefusedAndNamesTheFirst) {
    start(one_exchange, "  client_id: one-id\n");
    const auto from = recorder_->count();
    // The same configuration with a state directory of its own: only the port is shared.
    auto config = read_file(config_path_);
    const auto state = config.find("/state\n");
    ASSERT_NE(state, std::string::npos) << config;
    config.replace(state, 7, "/state-second\n");
    const auto second = dir_.write("second.yaml", config);

    const auto refused = run_command({gateway_binary(), "run", "-c", second}, 30s);
    EXPECT_EQ(refused.status, 1) << refused.output;
    const auto expected = "cannot bind UDP 127.0.0.1:" + std::to_string(udp_port_) +
                          ": Address already in use, held by process " +
                          std::to_string(gateway_->pid()) + " (";
    EXPECT_NE(refused.output.find(expected), std::string::npos) << refused.output;

    // The first one still has every datagram and its one MQTT session.
    for (std::uint16_t rid = 1; rid <= 5; ++rid) send(speed(rid, 100.0F + rid));
    const auto status = recorder_->wait_for_message(
        topic("pump/_status"),
        [](const std::string& p) { return nlohmann::json::parse(p)["received"] == 5; }, 15s, from);
    ASSERT_TRUE(status.has_value()) << gateway_->output();
    EXPECT_EQ(nlohmann::json::parse(status->payload)["missed"], 0);
    for (const auto& message : recorder_->messages_on(availability_topic())) {
        EXPECT_EQ(message.payload, "online");
    }
    EXPECT_EQ(gateway_->output().find("lost"), std::string::npos) << gateway_->output();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
