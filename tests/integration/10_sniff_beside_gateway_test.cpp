// `sniff` beside a running gateway: it prints every datagram while the gateway still receives
// every one of them (a passive capture takes nothing; a socket on the port would have).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;

class SniffBesideGatewayTest : public GatewayTest {};

TEST_F(SniffBesideGatewayTest, BothSeeEveryDatagram) {
    start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
              .length(4)
              .period_ms(1000)
              .timeout_ms(0)
              .tag("SPEED", "0.0", "real")
              .str());
    constexpr int count = 40;
    ChildProcess sniff({gateway_binary(), "sniff", "-c", config_path_, "--count",
                        std::to_string(count), "--duration", "60", "--interval", "0.5"});
    ASSERT_TRUE(sniff.wait_for_output("sniffing", 30s)) << sniff.output();

    const auto from = recorder_->count();
    for (std::uint16_t rid = 1; rid <= count; ++rid) {
        send(DatagramBuilder("10.0.0.2", 7, 4)
                 .request_id(rid)
                 .set("0.0", TagType::real, static_cast<float>(rid))
                 .build());
    }
    // The gateway: every datagram received, none missed.
    const auto status = recorder_->wait_for_message(
        topic("pump/_status"),
        [](const std::string& p) { return nlohmann::json::parse(p)["received"] == count; }, 15s,
        from);
    ASSERT_TRUE(status.has_value()) << gateway_->output();
    EXPECT_EQ(nlohmann::json::parse(status->payload)["missed"], 0);
    EXPECT_EQ(nlohmann::json::parse(status->payload)["accepted"], count);

    // sniff: the same datagrams, decoded, then its exit after --count.
    ASSERT_EQ(sniff.wait(30s), 0) << sniff.output();
    const auto output = sniff.output();
    for (int rid = 1; rid <= count; ++rid) {
        const auto line = " rid=" + std::to_string(rid) + " producer=10.0.0.2 exchange=7 ";
        EXPECT_NE(output.find(line), std::string::npos) << line << "\nin:\n" << output;
    }
    EXPECT_NE(output.find("[pump] SPEED=40.0"), std::string::npos) << output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
