// The `redundancy:` section (docs/redundancy.md): read with its defaults, and every mistake
// reported at its line and column.

#include <gtest/gtest.h>

#include "tests/adapters/yaml/loading.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

TEST(ReadRedundancy, OffUnlessAPairIsNamed) {
    EXPECT_FALSE(good(minimal_exchange).redundancy.enabled());
}

TEST(ReadRedundancy, ThePairWithItsDefaults) {
    const auto config = good("redundancy: { pair: turbine-gw }\n" + minimal_exchange);
    EXPECT_TRUE(config.redundancy.enabled());
    EXPECT_EQ(config.redundancy.pair, "turbine-gw");
    EXPECT_EQ(config.redundancy.takeover, 2000ms);
    EXPECT_FALSE(config.redundancy.priority.has_value());
}

TEST(ReadRedundancy, EveryKeyWritten) {
    const auto config =
        good("redundancy: { pair: p, takeover_ms: 800, priority: 100 }\n" + minimal_exchange);
    EXPECT_EQ(config.redundancy.takeover, 800ms);
    EXPECT_EQ(config.redundancy.priority, 100);
}

TEST(ReadRedundancy, MistakesAreReportedWhereTheyAre) {
    const auto text =
        dump(bad("redundancy:\n"
                 "  pair: turbine/gw\n"
                 "  takeover_ms: 100\n"
                 "  priority: -1\n"
                 "  takover_ms: 2000\n" +
                 minimal_exchange));
    EXPECT_NE(text.find("test.yaml:2:3: redundancy pair 'turbine/gw' contains '/', '+' or '#'"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:3:3: 'takeover_ms' 100 is outside 200..600000"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:4:3: 'priority' -1 is outside 0..65535"), std::string::npos)
        << text;
    EXPECT_NE(text.find("test.yaml:5:3: unknown key 'takover_ms' in redundancy"), std::string::npos)
        << text;
}

TEST(ReadRedundancy, ASectionWithoutAPairIsAnError) {
    const auto text = dump(bad("redundancy: { takeover_ms: 1000 }\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:1:13: redundancy lacks 'pair'"), std::string::npos) << text;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
