// `check` names the brokers of a list, in the order the gateway tries them.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace {

std::string checked(const std::string& url) {
    test::TempDir dir;
    const auto path = dir.write(
        "brokers.yaml", "mqtt:\n  url: " + url +
                            "\nexchanges:\n"
                            "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n");
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(run_check(path, out, err), 0) << err.str();
    return out.str();
}

TEST(CheckBrokers, AListIsPrintedInItsOrder) {
    const auto out = checked("[ tcp://b:1883, tcp://a:1883 ]");
    EXPECT_NE(out.find("brokers, tried in turn: tcp://b:1883, then tcp://a:1883\n"),
              std::string::npos)
        << out;
}

TEST(CheckBrokers, OneBrokerAddsNoLine) {
    const auto out = checked("tcp://a:1883");
    EXPECT_EQ(out.find("tried in turn"), std::string::npos) << out;
}

}  // namespace
}  // namespace eip2mqtt::app
