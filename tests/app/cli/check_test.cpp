// `check` names the brokers of a list, in the order the gateway tries them, and shows a scaled
// tag's scale in its byte map, and an array's or a string's bytes.

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

TEST(CheckByteMap, AScaledTagShowsItsScaleOnItsLine) {
    test::TempDir dir;
    const auto path = dir.write(
        "scaled.yaml",
        "exchanges:\n"
        "  - name: ex\n"
        "    producer_id: 10.0.0.1\n"
        "    exchange_id: 1\n"
        "    tags:\n"
        "      - { name: L, address: 0.0, type: int, unit: '%',\n"
        "          scale: { raw: [0, 32000], eu: [0, 100], clamp: true } }\n"
        "      - { name: F, address: 2.0, type: word, scale: { raw: [0, 65535], eu: [0, 500],"
        " sqrt: true } }\n"
        "      - { name: T, address: 4.0, type: dint, unit: degC, scale: { gain: 0.1, offset: -40 "
        "} }\n");
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_check(path, out, err), 0) << err.str();
    const auto text = out.str();
    EXPECT_NE(text.find("scale 0..32000 -> 0..100 %, clamped\n"), std::string::npos) << text;
    EXPECT_NE(text.find("scale sqrt 0..65535 -> 0..500\n"), std::string::npos) << text;
    EXPECT_NE(text.find("scale x 0.1 + -40 degC\n"), std::string::npos) << text;
}

TEST(CheckByteMap, ArraysAndStringsShowTheBytesTheyTake) {
    test::TempDir dir;
    const auto path = dir.write("shaped.yaml",
                                "exchanges:\n"
                                "  - name: ex\n"
                                "    producer_id: 10.0.0.1\n"
                                "    exchange_id: 1\n"
                                "    tags:\n"
                                "      - { name: T, address: 0.0, type: real, count: 4 }\n"
                                "      - { name: B, address: 16.0, type: string, length: 8 }\n"
                                "      - { name: F, address: 24.6, type: bit, count: 4 }\n");
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_check(path, out, err), 0) << err.str();
    const auto text = out.str();
    EXPECT_NE(text.find("real   16 bytes (4 elements) "), std::string::npos) << text;
    EXPECT_NE(text.find("string 8 bytes"), std::string::npos) << text;
    EXPECT_NE(text.find("bit    4 bits"), std::string::npos) << text;
    EXPECT_NE(text.find(", 26 bytes, period"), std::string::npos) << text;  // to the last bit
}

}  // namespace
}  // namespace eip2mqtt::app
