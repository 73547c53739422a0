#include "eip2mqtt/core/config/diagnostic.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::config {
namespace {

TEST(Diagnostic, FileLineColumn) {
    const Diagnostic d{{"eip2mqtt.yaml", 12, 5}, "unknown key 'lenght'"};
    EXPECT_EQ(d.to_string(), "eip2mqtt.yaml:12:5: error: unknown key 'lenght'");
}

TEST(Diagnostic, UnknownColumnIsLeftOut) {
    const Diagnostic d{{"points.csv", 3, 0}, "bad address"};
    EXPECT_EQ(d.to_string(), "points.csv:3: error: bad address");
}

TEST(Diagnostic, UnknownLineLeavesOutTheColumnToo) {
    const Diagnostic d{{"eip2mqtt.yaml", 0, 7}, "no exchanges"};
    EXPECT_EQ(d.to_string(), "eip2mqtt.yaml: error: no exchanges");
}

TEST(Diagnostic, NoFile) {
    EXPECT_EQ((Diagnostic{{"", 0, 0}, "oops"}).to_string(), "error: oops");
    EXPECT_EQ((Diagnostic{{"", 4, 2}, "oops"}).to_string(), "4:2: error: oops");
}

}  // namespace
}  // namespace eip2mqtt::core::config
