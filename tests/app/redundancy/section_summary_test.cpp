// What `check` says of the redundancy section, on its own (the command's output:
// tests/app/cli/check_redundancy_test.cpp).

#include "eip2mqtt/app/redundancy/section_summary.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

TEST(SectionSummary, NamesThePairItsTakeoverAndTheRenewalAQuarterOfIt) {
    core::config::RedundancySection section;
    section.pair = "line-4";
    section.takeover = std::chrono::milliseconds{1000};
    EXPECT_EQ(section_summary(section),
              "redundancy: pair line-4, takeover after 1000 ms, the lease renewed every 250 ms\n");
    section.priority = 3;
    EXPECT_EQ(section_summary(section),
              "redundancy: pair line-4, takeover after 1000 ms, the lease renewed every 250 ms, "
              "priority 3\n");
}

TEST(SectionSummary, NothingWithoutAPair) {
    EXPECT_EQ(section_summary(core::config::RedundancySection{}), "");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
