// `check` states the network load of the produced exchanges; every figure here is worked out by
// hand from the configuration below.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

/// Three produced exchanges and a consumed one, which puts nothing on the wire.
std::string config_with_link(const std::string& link_mbps) {
    return "gateway:\n  id: gw\nmqtt:\n  url: tcp://127.0.0.1:1883\n  base_topic: test\n"
           "eip:\n  link_mbps: " +
           link_mbps +
           "\nexchanges:\n"
           "  - { name: a, direction: produce, producer_id: 10.0.0.1, exchange_id: 1,\n"
           "      destination: 10.0.0.5, period_ms: 10, length: 100,\n"
           "      tags: [ { name: X, address: \"0.0\", type: byte } ] }\n"
           "  - { name: b, direction: produce, producer_id: 10.0.0.1, exchange_id: 2,\n"
           "      destination: 10.0.0.5, period_ms: 4, length: 1400,\n"
           "      tags: [ { name: X, address: \"0.0\", type: byte } ] }\n"
           "  - { name: in, direction: consume, producer_id: 10.0.0.9, exchange_id: 1,\n"
           "      period_ms: 2, length: 1400 }\n"
           "  - { name: d, direction: produce, producer_id: 10.0.0.1, exchange_id: 3,\n"
           "      destination: 224.0.7.1, period_ms: 3, length: 2,\n"
           "      tags: [ { name: X, address: \"0.0\", type: word } ] }\n";
}

struct Checked {
    int status;
    std::string out;
    std::string err;
};

Checked check(const std::string& link_mbps) {
    test::TempDir dir;
    const auto path = dir.write("load.yaml", config_with_link(link_mbps));
    std::ostringstream out;
    std::ostringstream err;
    const int status = run_check(path, out, err);
    return {status, out.str(), err.str()};
}

bool has(const std::string& text, const std::string& line) {
    return text.find(line) != std::string::npos;
}

// Per datagram on the wire: data + 98 bytes (8 preamble, 14 Ethernet, 20 IPv4, 8 UDP, 32 EIP
// header, 4 FCS, 12 gap).
//   a: 1000/10 = 100 datagrams/s x (100 + 98) x 8 = 158,400 bit/s
//   b: 1000/4 = 250 datagrams/s x (1400 + 98) x 8 = 2,996,000 bit/s
//   d: 1000/3 = 333.333 datagrams/s x (2 + 98) x 8 = 266,666.67 bit/s
//   all: 683.333 datagrams/s, 3,421,066.67 bit/s; to 10.0.0.5 (a, b): 350, 3,154,400.
// Phases, the i-th of 3 produced exchanges at period x i / 3: a 0, b 4/3 ms, d 2 ms.
TEST(CheckNetworkLoad, StatesTheLoadPerExchangeAndDestinationWithThePhases) {
    const auto result = check("10");
    ASSERT_EQ(result.status, 0) << result.out << result.err;
    for (const char* line :
         {"network load of the 3 produced exchanges: 683.333 datagrams/s, 3421067 bit/s on the "
          "wire, 34.21 % of eip.link_mbps 10\n",
          "  to 10.0.0.5: 2 exchanges, 350 datagrams/s, 3154400 bit/s\n",
          "  to 224.0.7.1: 1 exchange, 333.333 datagrams/s, 266667 bit/s\n",
          "  a: 100 datagrams/s, 158400 bit/s, first sent 0 ms after start\n",
          "  b: 250 datagrams/s, 2996000 bit/s, first sent 1.333333 ms after start\n",
          "  d: 333.333 datagrams/s, 266667 bit/s, first sent 2 ms after start\n"}) {
        EXPECT_TRUE(has(result.out, line)) << line << "\n" << result.out;
    }
    EXPECT_FALSE(has(result.out, "warning: the produced exchanges"));
}

TEST(CheckNetworkLoad, WarnsPastHalfOfTheLink) {
    const auto result = check("5");  // 3,421,066.67 / 5,000,000 = 68.42 %
    ASSERT_EQ(result.status, 0) << result.out << result.err;
    EXPECT_TRUE(has(result.out,
                    "  warning: the produced exchanges take 68.42 % of "
                    "eip.link_mbps 5, over half of the link"))
        << result.out;
}

TEST(CheckNetworkLoad, RefusesMoreThanTheLinkCarries) {
    const auto result = check("3");  // 3,421,066.67 / 3,000,000 = 114.04 %
    EXPECT_EQ(result.status, 1);
    EXPECT_TRUE(has(result.err, "error: the produced exchanges need 114.04 % of eip.link_mbps 3"))
        << result.err;
}

TEST(CheckNetworkLoad, TheLinkIs100MbitUnlessConfigured) {
    test::TempDir dir;
    auto text = config_with_link("10");
    text.erase(text.find("eip:\n  link_mbps: 10\n"), std::string("eip:\n  link_mbps: 10\n").size());
    const auto path = dir.write("default.yaml", text);
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_check(path, out, err), 0) << err.str();
    EXPECT_TRUE(has(out.str(), "3421067 bit/s on the wire, 3.42 % of eip.link_mbps 100\n"))
        << out.str();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
