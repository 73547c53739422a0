// JSON text the gateway writes by hand (adapters/mqtt/payload.hpp).

#include "eip2mqtt/adapters/mqtt/payload.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt {
namespace {

std::string json_string(std::string_view text) {
    std::string out = "x";  // appended to, never replaced
    append_json_string(out, text);
    return out;
}

TEST(JsonString, QuotesAndEscapesWhatJsonRequires) {
    EXPECT_EQ(json_string("PRESSAO"), R"(x"PRESSAO")");
    // Tag names may hold quotes and backslashes (issue #13: `_values` was invalid JSON).
    EXPECT_EQ(json_string(R"(SAY"HI\)"), R"(x"SAY\"HI\\")");
    EXPECT_EQ(json_string(std::string("A\x01"
                                      "B\n",
                                      4)),
              R"(x"A\u0001B\u000a")");
    EXPECT_EQ(json_string("Pressão/°C"), "x\"Pressão/°C\"");  // UTF-8 as is
    EXPECT_EQ(json_string(""), R"(x"")");
}

}  // namespace
}  // namespace eip2mqtt::adapters::mqtt
