// The conformance suite's instrument: the MQTT relay reads what a real client (Paho, which we did
// not write) puts on the wire, through to a real Mosquitto: the CONNECT's level, clean flag and
// will, each PUBLISH's topic, QoS and retain, SUBSCRIBE's filters and the DISCONNECT's reason;
// and the reader alone, fed byte by byte, torn packets and malformed ones.

#include "tests/support/mqtt_relay.hpp"

#include <gtest/gtest.h>
#include <mqtt/async_client.h>

#include <string>

#include "tests/support/mosquitto.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// A fixed header and remaining length before `body`.
std::string packet(std::uint8_t first, const std::string& body) {
    std::string out(1, static_cast<char>(first));
    auto length = body.size();
    do {
        auto b = static_cast<std::uint8_t>(length % 128);
        length /= 128;
        if (length > 0) b |= 0x80;
        out.push_back(static_cast<char>(b));
    } while (length > 0);
    return out + body;
}

std::string text(const std::string& s) {
    return std::string{static_cast<char>(s.size() >> 8), static_cast<char>(s.size() & 0xFF)} + s;
}

std::string bytes(std::initializer_list<int> values) {
    std::string out;
    for (const int v : values) out.push_back(static_cast<char>(v));
    return out;
}

TEST(MqttStreamReader, ReadsAnMqtt5ConnectWithItsWillFedByteByByte) {
    // Clean Start, will QoS 1 not retained, Session Expiry 0 among the properties.
    const auto connect =
        packet(0x10, text("MQTT") + bytes({5, 0x0E, 0, 30}) + bytes({5, 0x11, 0, 0, 0, 0}) +
                         text("node-1") + bytes({0}) + text("spBv1.0/g/NDEATH/n") + text("death"));
    MqttStreamReader reader;
    std::vector<MqttPacket> packets;
    for (const char c : connect) {
        for (auto& p : reader.feed(std::string_view(&c, 1))) packets.push_back(std::move(p));
    }
    ASSERT_EQ(packets.size(), 1u);
    const auto& p = packets[0];
    EXPECT_EQ(p.type, PacketType::connect) << p.error;
    EXPECT_EQ(p.protocol_level, 5);
    EXPECT_TRUE(p.clean);
    EXPECT_EQ(p.session_expiry, 0u);
    EXPECT_EQ(p.client_id, "node-1");
    ASSERT_TRUE(p.will.has_value());
    EXPECT_EQ(p.will->topic, "spBv1.0/g/NDEATH/n");
    EXPECT_EQ(p.will->payload, "death");
    EXPECT_EQ(p.will->qos, 1);
    EXPECT_FALSE(p.will->retain);
    EXPECT_EQ(reader.protocol_level(), 5);
}

TEST(MqttStreamReader, ReadsPublishAndDisconnectAtTheConnectsLevel) {
    MqttStreamReader reader;
    reader.set_protocol_level(5);
    const auto publish = packet(0x33, text("a/b") + bytes({0, 7}) + bytes({0}) + "xyz");
    const auto disconnect_with_will = packet(0xE0, bytes({0x04, 0}));
    const auto plain_disconnect = packet(0xE0, "");
    const auto packets = reader.feed(publish + disconnect_with_will + plain_disconnect);
    ASSERT_EQ(packets.size(), 3u);
    EXPECT_EQ(packets[0].type, PacketType::publish);
    EXPECT_EQ(packets[0].topic, "a/b");
    EXPECT_EQ(packets[0].payload, "xyz");
    EXPECT_EQ(packets[0].qos, 1);
    EXPECT_TRUE(packets[0].retain);
    EXPECT_EQ(packets[1].reason, 0x04);
    EXPECT_EQ(packets[2].reason, 0x00);  // MQTT 5: no body is Normal disconnection
    MqttStreamReader v311;
    EXPECT_FALSE(v311.feed(plain_disconnect).at(0).reason.has_value());  // 3.1.1 has none
}

TEST(MqttStreamReader, AMalformedPacketIsReportedAndTheStreamGoesOn) {
    MqttStreamReader reader;
    const auto packets =
        reader.feed(packet(0x10, text("MQIsdp") + bytes({3, 2, 0, 30})) +   // 3.1's name
                    packet(0x32, text("a/very/long/topic").substr(0, 4)) +  // ends early
                    packet(0xC0, ""));
    ASSERT_EQ(packets.size(), 3u);
    EXPECT_EQ(packets[0].type, PacketType::malformed);
    EXPECT_NE(packets[0].error.find("protocol name"), std::string::npos);
    EXPECT_EQ(packets[1].type, PacketType::malformed);
    EXPECT_EQ(packets[2].type, PacketType::pingreq);
    EXPECT_TRUE(reader.feed(bytes({0x30})).empty());  // a header without its length yet
}

TEST(MqttRelay, RecordsWhatARealClientSendsAndTheBrokersAnswers) {
    Mosquitto broker;
    MqttRelay relay(broker.port());
    mqtt::async_client client(relay.url(), "relay-test", mqtt::create_options(MQTTVERSION_5));
    auto options =
        mqtt::connect_options_builder()
            .mqtt_version(MQTTVERSION_5)
            .clean_start(true)
            .will(mqtt::will_options(std::string("t/will"), std::string("gone"), 1, false))
            .finalize();
    client.connect(options)->wait_for(10s);
    client.subscribe("t/cmd", 1)->wait_for(10s);
    client.publish(mqtt::make_message("t/data", "v", 0, false))->wait_for(10s);
    client.publish(mqtt::make_message("t/state", "s", 1, true))->wait_for(10s);
    client.disconnect()->wait_for(10s);
    ASSERT_TRUE(relay.wait_for([](const MqttRelay::Events& events) {
        return !events.empty() && events.back().closed();
    })) << "the connection never closed";

    std::vector<MqttPacket> sent;
    bool connack = false;
    for (const auto& e : relay.events()) {
        EXPECT_EQ(e.connection, 0u);
        if (e.closed()) continue;
        if (e.from_client() && e.packet->type != PacketType::pingreq) sent.push_back(*e.packet);
        if (!e.from_client() && e.packet->type == PacketType::connack) connack = true;
    }
    EXPECT_TRUE(connack);
    ASSERT_EQ(sent.size(), 5u);
    EXPECT_EQ(sent[0].type, PacketType::connect);
    EXPECT_EQ(sent[0].protocol_level, 5);
    EXPECT_TRUE(sent[0].clean);
    ASSERT_TRUE(sent[0].will.has_value());
    EXPECT_EQ(sent[0].will->topic, "t/will");
    EXPECT_EQ(sent[0].will->qos, 1);
    EXPECT_EQ(sent[1].filters, std::vector<std::string>{"t/cmd"});
    EXPECT_EQ(sent[2].topic, "t/data");
    EXPECT_EQ(sent[2].qos, 0);
    EXPECT_FALSE(sent[2].retain);
    EXPECT_EQ(sent[3].qos, 1);
    EXPECT_TRUE(sent[3].retain);
    EXPECT_EQ(sent[4].type, PacketType::disconnect);
    EXPECT_EQ(sent[4].reason, 0x00);  // Paho's plain DISCONNECT: Normal disconnection
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
