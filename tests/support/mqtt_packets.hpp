#pragma once
/// MQTT 3.1.1 and 5 control packets as a relay between a client and its broker sees them, read
/// from the byte stream of one direction of one connection: what the conformance checks judge
/// (CONNECT with its clean flag and will, PUBLISH with its QoS and retain, SUBSCRIBE, DISCONNECT
/// with its reason code). Not a broker, and not lenient: a malformed packet is reported as such.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::test {

enum class PacketType : std::uint8_t {
    connect = 1,
    connack = 2,
    publish = 3,
    puback = 4,
    subscribe = 8,
    suback = 9,
    pingreq = 12,
    pingresp = 13,
    disconnect = 14,
    other = 0,  ///< a type the checks do not read (PUBREC, UNSUBSCRIBE, AUTH...)
    malformed = 255,
};

struct WillMessage {
    std::string topic;
    std::string payload;
    int qos = 0;
    bool retain = false;
};

struct MqttPacket {
    PacketType type = PacketType::other;
    std::string error;           ///< malformed: what is wrong
    std::size_t wire_bytes = 0;  ///< the whole packet, fixed header included
    // CONNECT
    int protocol_level = 0;                       ///< 4: MQTT 3.1.1, 5: MQTT 5
    bool clean = false;                           ///< Clean Session (3.1.1), Clean Start (5)
    std::optional<std::uint32_t> session_expiry;  ///< MQTT 5 property 0x11, when present
    std::string client_id;
    std::optional<WillMessage> will;
    // PUBLISH
    std::string topic;
    std::string payload;
    int qos = 0;
    bool retain = false;
    bool dup = false;
    std::optional<std::uint16_t> topic_alias;  ///< MQTT 5 property 0x23, when present
    // SUBSCRIBE
    std::vector<std::string> filters;
    // DISCONNECT (MQTT 5; 0 when the packet has none, as the specification reads it), CONNACK
    std::optional<std::uint8_t> reason;
};

/// The packets of one direction of one connection, fed as the bytes come. The protocol level
/// is the CONNECT's: the relay hands it to the other direction's reader (set_protocol_level).
class MqttStreamReader {
public:
    /// Appends `bytes`; returns the packets they completed, in order.
    std::vector<MqttPacket> feed(std::string_view bytes);
    void set_protocol_level(int level) { level_ = level; }
    int protocol_level() const { return level_; }

private:
    MqttPacket parse(std::uint8_t first, std::string_view body);
    std::string buffer_;
    int level_ = 4;
};

}  // namespace eip2mqtt::test
