// The relay's MQTT reader: fixed header, remaining length, and the fields the conformance checks
// read of CONNECT, PUBLISH, SUBSCRIBE, CONNACK and DISCONNECT, in MQTT 3.1.1 and 5.

#include "tests/support/mqtt_packets.hpp"

#include <stdexcept>

namespace eip2mqtt::test {
namespace {

/// A cursor over one packet's body; every read past its end throws.
class Body {
public:
    explicit Body(std::string_view bytes) : bytes_(bytes) {}
    bool done() const { return at_ == bytes_.size(); }
    std::uint8_t byte() {
        need(1);
        return static_cast<std::uint8_t>(bytes_[at_++]);
    }
    std::uint16_t u16() {
        const auto high = byte();
        return static_cast<std::uint16_t>(high << 8 | byte());
    }
    std::uint32_t u32() {
        std::uint32_t value = 0;
        for (int i = 0; i < 4; ++i) value = value << 8 | byte();
        return value;
    }
    std::uint32_t varint() {
        std::uint32_t value = 0;
        for (int shift = 0; shift < 28; shift += 7) {
            const auto b = byte();
            value |= static_cast<std::uint32_t>(b & 0x7F) << shift;
            if ((b & 0x80) == 0) return value;
        }
        throw std::runtime_error("a variable byte integer over 4 bytes");
    }
    std::string text() {
        const auto size = u16();
        return take(size);
    }
    std::string take(std::size_t size) {
        need(size);
        std::string out(bytes_.substr(at_, size));
        at_ += size;
        return out;
    }
    std::string rest() { return take(bytes_.size() - at_); }

private:
    void need(std::size_t size) const {
        if (bytes_.size() - at_ < size) throw std::runtime_error("the packet ends early");
    }
    std::string_view bytes_;
    std::size_t at_ = 0;
};

/// The MQTT 5 properties the checks read.
struct ReadProperties {
    std::optional<std::uint32_t> session_expiry;  ///< 0x11
    std::optional<std::uint16_t> topic_alias;     ///< 0x23
};

/// MQTT 5 properties: their length, then id/value pairs. Returns those of ReadProperties when
/// present; skips the rest by their types.
ReadProperties read_properties(Body& body) {
    const auto length = body.varint();
    const auto bytes = body.take(length);  // outlives the cursor over it
    Body properties(bytes);
    ReadProperties read;
    auto& session_expiry = read.session_expiry;
    while (!properties.done()) {
        const auto id = properties.varint();
        switch (id) {
            case 0x01:
            case 0x17:
            case 0x19:
            case 0x24:
            case 0x25:
            case 0x28:
            case 0x29:
            case 0x2A:
                properties.byte();
                break;
            case 0x23:
                read.topic_alias = properties.u16();
                break;
            case 0x13:
            case 0x21:
            case 0x22:
                properties.u16();
                break;
            case 0x11:
                session_expiry = properties.u32();
                break;
            case 0x02:
            case 0x18:
            case 0x27:
                properties.u32();
                break;
            case 0x0B:
                properties.varint();
                break;
            case 0x03:
            case 0x08:
            case 0x09:
            case 0x12:
            case 0x15:
            case 0x16:
            case 0x1A:
            case 0x1C:
            case 0x1F:
                properties.text();
                break;
            case 0x26:
                properties.text();
                properties.text();
                break;
            default:
                throw std::runtime_error("unknown property " + std::to_string(id));
        }
    }
    return read;
}

void parse_connect(Body& body, MqttPacket& packet) {
    const auto protocol = body.text();
    if (protocol != "MQTT") throw std::runtime_error("protocol name '" + protocol + "'");
    packet.protocol_level = body.byte();
    const auto flags = body.byte();
    packet.clean = (flags & 0x02) != 0;
    body.u16();  // keep alive
    const bool v5 = packet.protocol_level == 5;
    if (v5) packet.session_expiry = read_properties(body).session_expiry;
    packet.client_id = body.text();
    if ((flags & 0x04) != 0) {
        WillMessage will;
        if (v5) read_properties(body);
        will.topic = body.text();
        will.payload = body.text();  // binary data: the same two-byte length
        will.qos = (flags >> 3) & 0x03;
        will.retain = (flags & 0x20) != 0;
        packet.will = std::move(will);
    }
    if ((flags & 0x80) != 0) body.text();  // user name
    if ((flags & 0x40) != 0) body.text();  // password
}

void parse_publish(std::uint8_t first, int level, Body& body, MqttPacket& packet) {
    packet.dup = (first & 0x08) != 0;
    packet.qos = (first >> 1) & 0x03;
    packet.retain = (first & 0x01) != 0;
    if (packet.qos == 3) throw std::runtime_error("QoS 3");
    packet.topic = body.text();
    if (packet.qos > 0) body.u16();  // packet identifier
    if (level == 5) packet.topic_alias = read_properties(body).topic_alias;
    packet.payload = body.rest();
}

void parse_subscribe(int level, Body& body, MqttPacket& packet) {
    body.u16();  // packet identifier
    if (level == 5) read_properties(body);
    while (!body.done()) {
        packet.filters.push_back(body.text());
        body.byte();  // options
    }
}

}  // namespace

std::vector<MqttPacket> MqttStreamReader::feed(std::string_view bytes) {
    buffer_.append(bytes);
    std::vector<MqttPacket> packets;
    while (buffer_.size() >= 2) {
        std::size_t length = 0;
        std::size_t header = 1;
        bool complete = false;
        for (int shift = 0; header < buffer_.size() && shift < 28; shift += 7) {
            const auto b = static_cast<std::uint8_t>(buffer_[header++]);
            length |= static_cast<std::size_t>(b & 0x7F) << shift;
            if ((b & 0x80) == 0) {
                complete = true;
                break;
            }
        }
        if (!complete || buffer_.size() < header + length) break;
        packets.push_back(parse(static_cast<std::uint8_t>(buffer_[0]),
                                std::string_view(buffer_).substr(header, length)));
        packets.back().wire_bytes = header + length;
        buffer_.erase(0, header + length);
    }
    return packets;
}

MqttPacket MqttStreamReader::parse(std::uint8_t first, std::string_view bytes) {
    MqttPacket packet;
    packet.type = static_cast<PacketType>(first >> 4);
    Body body(bytes);
    try {
        switch (packet.type) {
            case PacketType::connect:
                parse_connect(body, packet);
                level_ = packet.protocol_level;
                break;
            case PacketType::publish:
                parse_publish(first, level_, body, packet);
                break;
            case PacketType::subscribe:
                parse_subscribe(level_, body, packet);
                break;
            case PacketType::connack:
                body.byte();  // session present
                packet.reason = body.byte();
                break;
            case PacketType::disconnect:
                // MQTT 5: a DISCONNECT without a body is reason 0x00, Normal disconnection.
                if (level_ == 5) packet.reason = body.done() ? 0 : body.byte();
                break;
            case PacketType::puback:
            case PacketType::suback:
            case PacketType::pingreq:
            case PacketType::pingresp:
                break;
            default:
                packet.type = PacketType::other;
        }
    } catch (const std::exception& e) {
        packet.type = PacketType::malformed;
        packet.error = e.what();
    }
    return packet;
}

}  // namespace eip2mqtt::test
