// The gateway's optional Prometheus endpoint serves its live counters, on the one address
// it is given.

#include <signal.h>

#include <fstream>
#include <thread>

#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using namespace std::chrono_literals;

class PrometheusTest : public GatewayTest {};

TEST_F(PrometheusTest, EndpointServesPerExchangeCountersAndMqttState) {
    const auto port = free_tcp_port();
    start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
              .length(4)
              .period_ms(1000)
              .tag("SPEED", "0.0", "dint")
              .str());
    // The metrics section is added by rewriting the file and restarting the gateway.
    gateway_->signal(SIGTERM);
    ASSERT_EQ(gateway_->wait(10s), 0);
    std::ofstream(config_path_, std::ios::app) << "metrics:\n  listen: 127.0.0.1:" << port << "\n";
    start_gateway();
    for (std::uint16_t rid = 1; rid <= 3; ++rid) {
        send(DatagramBuilder("10.0.0.2", 7, 4)
                 .request_id(rid * 2)
                 .set("0.0", TagType::dint, std::int64_t{rid})
                 .build());
    }
    expect_field(topic("pump/SPEED"), "value", "3");
    // The endpoint is refreshed once a second: poll it (bounded) until it shows the datagrams.
    std::string page;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (std::chrono::steady_clock::now() < deadline) {
        page = http_get(port, "/metrics");
        if (page.find(
                R"(eip2mqtt_exchange_accepted_total{direction="consume",exchange="pump"} 3)") !=
            std::string::npos) {
            break;
        }
        std::this_thread::sleep_for(100ms);
    }
    EXPECT_NE(
        page.find(R"(eip2mqtt_exchange_accepted_total{direction="consume",exchange="pump"} 3)"),
        std::string::npos)
        << page;
    EXPECT_NE(page.find(R"(eip2mqtt_exchange_missed_total{direction="consume",exchange="pump"} 2)"),
              std::string::npos)
        << page;
    EXPECT_NE(page.find("eip2mqtt_mqtt_connected 1"), std::string::npos) << page;
}

TEST(PrometheusListen, CheckAndRunRefuseAListOfAddressesAtItsLineAndColumn) {
    // civetweb takes "a,b" as two listeners: check passed it and run opened the second.
    const auto first = free_tcp_port();
    const auto second = free_tcp_port();
    TempDir dir;
    const auto path = dir.write("list.yaml",
                                "mqtt:\n  url: tcp://127.0.0.1:1\nmetrics:\n"
                                "  listen: 127.0.0.1:" +
                                    std::to_string(first) + ",127.0.0.1:" + std::to_string(second) +
                                    "\nexchanges:\n"
                                    "  - { name: ex, producer_id: 10.0.0.1, "
                                    "exchange_id: 1, length: 4 }\n");
    const auto check = run_command({gateway_binary(), "check", "-c", path}, 10s);
    EXPECT_EQ(check.status, 1) << check.output;
    EXPECT_NE(check.output.find(path + ":4:3: error: listen '127.0.0.1:"), std::string::npos)
        << check.output;
    EXPECT_NE(check.output.find("is not one host:port"), std::string::npos) << check.output;
    // run refuses the file as check does, before it listens on anything.
    const auto run = run_command({gateway_binary(), "run", "-c", path}, 10s);
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_NE(run.output.find("is not one host:port"), std::string::npos) << run.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
