// `check` names the brokers of a list, in the order the gateway tries them, shows a scaled
// tag's scale in its byte map and an array's or a string's bytes, and says what MQTT 3.1.1
// cannot carry.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

std::string checked_brokers(const std::string& url) {
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
    const auto out = checked_brokers("[ tcp://b:1883, tcp://a:1883 ]");
    EXPECT_NE(out.find("brokers, tried in turn: tcp://b:1883, then tcp://a:1883\n"),
              std::string::npos)
        << out;
}

TEST(CheckBrokers, OneBrokerAddsNoLine) {
    const auto out = checked_brokers("tcp://a:1883");
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

TEST(CheckMqtt5, MetadataKeysAreSaidToBeIgnoredOverMqtt311) {
    test::TempDir dir;
    const auto text = [](const std::string& version) {
        return "mqtt:\n  version: " + version +
               "\n  properties: [unit]\n  message_expiry_s: 60\n  topic_aliases: true\n"
               "  describe_payloads: false\n"
               "exchanges:\n  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n";
    };
    std::ostringstream out;
    std::ostringstream err;
    const auto v3 = dir.write("v3.yaml", text("3.1.1"));
    ASSERT_EQ(run_check(v3, out, err), 0) << err.str();
    EXPECT_NE(out.str().find(v3 + ":3:3: warning: mqtt.properties is ignored with MQTT 3.1.1"),
              std::string::npos)
        << out.str();
    EXPECT_NE(out.str().find("mqtt.topic_aliases is ignored"), std::string::npos);
    EXPECT_NE(out.str().find("mqtt.describe_payloads is ignored"), std::string::npos);
    std::ostringstream out5;
    ASSERT_EQ(run_check(dir.write("v5.yaml", text("5")), out5, err), 0) << err.str();
    EXPECT_EQ(out5.str().find("is ignored"), std::string::npos) << out5.str();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
