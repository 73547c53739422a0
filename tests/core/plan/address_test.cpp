#include "eip2mqtt/core/plan/address.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TEST(Addresses, ByteDotBit) {
    EXPECT_EQ(parse_address("119.5"), (Address{119, 5}));
    EXPECT_EQ(parse_address("0.0"), (Address{0, 0}));
    EXPECT_EQ(parse_address("120.7"), (Address{120, 7}));
    EXPECT_EQ(parse_address("65535.0"), (Address{65535, 0}));
}

TEST(Addresses, ByteAloneMeansBitZero) {
    EXPECT_EQ(parse_address("126"), (Address{126, 0}));
    EXPECT_EQ(parse_address("0"), (Address{0, 0}));
}

TEST(PointLists, Section6AddressesParse) {
    EXPECT_EQ(parse_address("126.0"), (Address{126, 0}));
    EXPECT_EQ(parse_address("208.0"), (Address{208, 0}));
    EXPECT_EQ(parse_address("368.0"), (Address{368, 0}));
}

TEST(Addresses, RejectsMalformedText) {
    for (const char* text : {"", ".", "1.", ".1", "1.8", "1.10", "65536", "65536.0", "-1.0", "+1.0",
                             " 1.0", "1.0 ", "1,0", "a.b", "1.2.3", "0x10"}) {
        EXPECT_EQ(parse_address(text), std::nullopt) << text;
    }
}

TEST(Addresses, PrintsByteDotBit) {
    EXPECT_EQ(to_string(Address{126, 0}), "126.0");
    EXPECT_EQ(to_string(Address{119, 5}), "119.5");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
