// connection_reasons: what the log says when the broker refuses or ends a connection for a
// cause outside the gateway (another client with its id, a broker without MQTT 5).

#include "adapters/mqtt/detail/connection_reasons.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(ConnectionReasons, SessionTakenOverNamesTheClientId) {
    const auto text = describe_disconnect(0x8E, "Session taken over", "gw-1");
    EXPECT_TRUE(contains(text,
                         "another client connected with the same client id 'gw-1' (MQTT 5 "
                         "reason 0x8E"))
        << text;
    EXPECT_TRUE(contains(text, "give each its own mqtt.client_id")) << text;
}

TEST(ConnectionReasons, OtherDisconnectsKeepTheBrokersWordsAndCode) {
    EXPECT_EQ(describe_disconnect(0x8B, "Server shutting down", "gw-1"),
              "broker sent DISCONNECT: Server shutting down (MQTT 5 reason 0x8B)");
}

TEST(ConnectionReasons, AnMqtt5RefusalAdvisesVersion311) {
    for (const auto& [code, failure] :
         std::vector<std::pair<int, std::string>>{{-1, "Failure: TCP connect completion failure"},
                                                  {1, "Unknown error code 1"},
                                                  {0x84, "Unsupported Protocol Version"}}) {
        const auto refusal = mqtt5_refusal(code, failure, false);
        ASSERT_TRUE(refusal.has_value()) << failure;
        EXPECT_TRUE(contains(*refusal, "the broker refused MQTT 5")) << *refusal;
        EXPECT_TRUE(contains(*refusal, "set mqtt.version: 3.1.1")) << *refusal;
    }
}

TEST(ConnectionReasons, AConnectionClosedBeforeTheConnackMayAlsoBeAProxyWhoseBrokerIsDown) {
    // A TCP proxy or load balancer accepts, then closes once it finds no broker behind it: the
    // same words from Paho as a 3.1.1 broker's refusal.
    const auto refusal = mqtt5_refusal(-1, "Failure: TCP connect completion failure", false);
    ASSERT_TRUE(refusal.has_value());
    EXPECT_TRUE(contains(*refusal, "a proxy or load balancer does whose broker is down"))
        << *refusal;
}

TEST(ConnectionReasons, OtherConnectFailuresGetNoVersionAdvice) {
    EXPECT_FALSE(mqtt5_refusal(-1, "Failure: TCP/TLS connect failure", false));  // no listener
    EXPECT_FALSE(mqtt5_refusal(0x87, "Not authorized", false));
    EXPECT_FALSE(mqtt5_refusal(5, "Not authorized", false));
}

TEST(ConnectionReasons, OverTlsAClosedConnectionOnlyMayMeanMqtt311) {
    // A broker that requires a client certificate closes after the TLS 1.3 handshake, as one
    // that refuses MQTT 5 does: the TLS checks are named first, the version as a possibility.
    const auto refusal = mqtt5_refusal(-1, "Failure: TCP connect completion failure", true);
    ASSERT_TRUE(refusal.has_value());
    EXPECT_FALSE(contains(*refusal, "the broker refused MQTT 5")) << *refusal;
    EXPECT_TRUE(contains(*refusal, "if the TLS settings are right")) << *refusal;
    EXPECT_TRUE(contains(*refusal, "set mqtt.version: 3.1.1")) << *refusal;
}

TEST(SilentLossPattern, ThreeShortSilentLossesInARowMakeThePattern) {
    SilentLossPattern pattern;
    EXPECT_FALSE(pattern.on_loss(true, 1300ms));
    EXPECT_FALSE(pattern.on_loss(true, 2s));
    EXPECT_TRUE(pattern.on_loss(true, 250ms));
    EXPECT_TRUE(pattern.on_loss(true, 29s));  // and it goes on while they do
}

TEST(SilentLossPattern, ALongConnectionOrAGivenReasonStartsAgain) {
    SilentLossPattern pattern;
    pattern.on_loss(true, 1s);
    pattern.on_loss(true, 1s);
    EXPECT_FALSE(pattern.on_loss(true, 30s));  // lived long enough: not a take-over
    pattern.on_loss(true, 1s);
    pattern.on_loss(true, 1s);
    EXPECT_FALSE(pattern.on_loss(false, 1s));  // a DISCONNECT said why
    EXPECT_FALSE(pattern.on_loss(true, 1s));
}

TEST(SilentLossPattern, TheExplanationNamesTheClientId) {
    const auto text = SilentLossPattern::explain("gw-1");
    EXPECT_TRUE(contains(text, "3 connections in a row were closed without a reason")) << text;
    EXPECT_TRUE(contains(text, "same client id 'gw-1'")) << text;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
