// /healthz and /readyz of the running gateway, on its metrics listener: connected and not,
// fresh and stale; and slow clients do not take them away.

#include <memory>
#include <thread>
#include <vector>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using namespace std::chrono_literals;

class HealthTest : public GatewayTest {
protected:
    /// Polls `path` (bounded) until its response contains `text`, sending a datagram of the
    /// exchange before each poll while `fresh`; the last response.
    std::string wait_for(const std::string& path, const std::string& text, bool fresh) {
        std::string response;
        const auto deadline = std::chrono::steady_clock::now() + 30s;
        while (std::chrono::steady_clock::now() < deadline) {
            if (fresh) {
                ++request_id_;
                send(DatagramBuilder("10.0.0.2", 7, 4)
                         .request_id(request_id_)
                         .set("0.0", TagType::dint, std::int64_t{request_id_})
                         .build());
            }
            response = http_get(port_, path);
            if (response.find(text) != std::string::npos) break;
            std::this_thread::sleep_for(100ms);
        }
        return response;
    }

    std::uint16_t port_ = free_tcp_port();
    std::uint16_t request_id_ = 0;
};

TEST_F(HealthTest, ReadyzFollowsTheBrokerAndTheExchangesWhileHealthzStaysUp) {
    GatewayOptions options;
    options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port_) + "\n";
    start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
              .length(4)
              .period_ms(100)
              .timeout_ms(300)
              .tag("SPEED", "0.0", "dint")
              .str(),
          "", options);

    // Connected and fresh.
    auto ready = wait_for("/readyz", "\r\n\r\nready\n", true);
    EXPECT_NE(ready.find(" 200 OK\r\n"), std::string::npos) << ready;
    EXPECT_NE(http_get(port_, "/healthz").find("\r\n\r\nok\n"), std::string::npos);

    // Stale: no datagram for longer than timeout_ms.
    const auto stale = wait_for("/readyz", "exchange pump is stale", false);
    EXPECT_NE(stale.find(" 503 "), std::string::npos) << stale;
    EXPECT_EQ(stale.find("MQTT"), std::string::npos) << stale;
    EXPECT_NE(http_get(port_, "/healthz").find(" 200 OK\r\n"), std::string::npos);

    // Not connected: the broker gone.
    broker_->stop();
    const auto disconnected = wait_for("/readyz", "MQTT is not connected", true);
    EXPECT_NE(disconnected.find(" 503 "), std::string::npos) << disconnected;
    EXPECT_NE(http_get(port_, "/healthz").find(" 200 OK\r\n"), std::string::npos);

    // Connected and fresh again.
    broker_->start();
    ready = wait_for("/readyz", "\r\n\r\nready\n", true);
    EXPECT_NE(ready.find(" 200 OK\r\n"), std::string::npos) << ready;
}

TEST_F(HealthTest, HealthzAnswersEveryProbeWhileSlowClientsHoldConnections) {
    GatewayOptions options;
    options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port_) + "\n";
    start(ExchangeYaml::consume("pump", "10.0.0.2", 7).length(4).tag("SPEED", "0.0", "dint").str(),
          "", options);
    const auto up = wait_for("/healthz", "\r\n\r\nok\n", false);
    ASSERT_NE(up.find(" 200 OK\r\n"), std::string::npos) << up;

    // Twelve connections that send nothing or half a request line, as a hostile or broken
    // client does: two of them made 28 of 32 probes fail over a minute.
    std::vector<std::unique_ptr<SilentClient>> clients;
    for (int i = 0; i < 12; ++i) {
        clients.push_back(std::make_unique<SilentClient>(port_, i % 2 ? "GET /hea" : ""));
        ASSERT_TRUE(clients.back()->connected());
    }
    // Over 4 s: longer than the listener's request timeout, so past the slow clients' end.
    const auto until = std::chrono::steady_clock::now() + 4s;
    int probes = 0;
    while (probes < 10 || std::chrono::steady_clock::now() < until) {
        const auto response = http_get(port_, "/healthz");
        ASSERT_NE(response.find(" 200 OK\r\n"), std::string::npos)
            << "probe " << probes << ": " << response;
        ++probes;
        std::this_thread::sleep_for(100ms);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
