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

TEST(FileName, CopiesShareOneString) {
    const FileName name("plant/eip2mqtt-turbine-hall.yaml");
    const Mark a{name, 1, 1};
    const Mark b = a;
    // One heap string for every mark of a file, however many marks there are.
    EXPECT_EQ(&a.file.str(), &name.str());
    EXPECT_EQ(&b.file.str(), &name.str());
    EXPECT_EQ(b.file, "plant/eip2mqtt-turbine-hall.yaml");
}

TEST(FileName, ComparesByText) {
    EXPECT_EQ(FileName("a.yaml"), FileName(std::string("a.yaml")));  // made apart, one name
    EXPECT_EQ(&FileName("a.yaml").str(), &FileName("a.yaml").str());
    EXPECT_NE(FileName("a.yaml"), FileName("b.csv"));
    EXPECT_LT(FileName("a.yaml"), FileName("b.csv"));
    EXPECT_EQ(FileName(), FileName(""));
    EXPECT_TRUE(FileName().empty());
    EXPECT_EQ(FileName().str(), "");
}

}  // namespace
}  // namespace eip2mqtt::core::config
