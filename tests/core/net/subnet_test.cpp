#include "eip2mqtt/core/net/subnet.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::core::net {
namespace EIP2MQTT_THIS_FILE {

std::uint32_t ip(std::string_view dotted) { return parse_subnet(dotted).value().address; }

TEST(Subnet, CidrClearsHostBitsAndContainsItsAddresses) {
    const auto subnet = parse_subnet("10.20.0.7/24").value();
    EXPECT_EQ(to_string(subnet), "10.20.0.0/24");
    EXPECT_TRUE(subnet.contains(ip("10.20.0.1")));
    EXPECT_TRUE(subnet.contains(ip("10.20.0.255")));
    EXPECT_FALSE(subnet.contains(ip("10.20.1.0")));
}

TEST(Subnet, AnAddressAloneIsOneHostAndSlashZeroIsEveryHost) {
    const auto host = parse_subnet("127.0.0.1").value();
    EXPECT_EQ(host.prefix, 32);
    EXPECT_TRUE(host.contains(ip("127.0.0.1")));
    EXPECT_FALSE(host.contains(ip("127.0.0.2")));
    EXPECT_TRUE(parse_subnet("0.0.0.0/0")->contains(ip("203.0.113.9")));
}

TEST(Subnet, MalformedTextIsRefused) {
    for (const auto text : {"", "10.20", "10.20.0.0/", "10.20.0.0/33", "10.20.0.0/-1",
                            "10.20.0.256/24", "2954172332", "10.20.0.0/24x", "fe80::1"}) {
        EXPECT_FALSE(parse_subnet(text).has_value()) << text;
    }
}

TEST(Subnet, AllowedIsAnyOfTheList) {
    const std::vector<Subnet> list{*parse_subnet("10.0.0.0/8"), *parse_subnet("192.168.1.5")};
    EXPECT_TRUE(allowed(list, ip("10.9.9.9")));
    EXPECT_TRUE(allowed(list, ip("192.168.1.5")));
    EXPECT_FALSE(allowed(list, ip("192.168.1.6")));
    EXPECT_FALSE(allowed({}, ip("10.9.9.9")));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::net
