// `check` says how a pair's lease runs.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

std::string checked(const std::string& section) {
    test::TempDir dir;
    const auto path = dir.write(
        "pair.yaml", section +
                         "exchanges:\n"
                         "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n");
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(run_check(path, out, err), 0) << err.str();
    return out.str();
}

TEST(CheckRedundancy, ThePairItsTakeoverAndItsRenewalAreShown) {
    const auto out = checked("redundancy: { pair: turbine-gw, takeover_ms: 2000, priority: 7 }\n");
    EXPECT_NE(out.find("redundancy: pair turbine-gw, takeover after 2000 ms, the lease renewed "
                       "every 500 ms, priority 7\n"),
              std::string::npos)
        << out;
}

TEST(CheckRedundancy, SparkplugInAPairIsOneEdgeNodeWithoutAWarning) {
    const auto out = checked(
        "redundancy: { pair: turbine-gw }\n"
        "sparkplug: { group_id: plant1 }\n");
    EXPECT_NE(out.find("redundancy: pair turbine-gw"), std::string::npos) << out;
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
}

TEST(CheckRedundancy, NoPairNoLine) {
    EXPECT_EQ(checked("").find("redundancy"), std::string::npos);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
