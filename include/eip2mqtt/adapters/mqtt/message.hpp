#pragma once
/// An MQTT publication as the gateway hands it to the client adapter.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace eip2mqtt::adapters::mqtt {

struct Message {
    std::string topic;
    std::string payload;
    int qos = 0;
    bool retain : 1 = false;
    /// Latest value wins: a newer message with the same topic replaces this one while it is
    /// still queued. Off for messages that must each be delivered (write results).
    bool coalesce : 1 = true;
    /// Batch mode's `{exchange}/_values`: queued in a lane of its own, served in turn with the
    /// others, so that a saturated per-tag flow cannot starve it (nor it the per-tag topics).
    bool batch_lane : 1 = false;
    /// MQTT 5 user property `historical=true`: a replayed sample, not a live one.
    bool historical : 1 = false;
    /// A live value (a tag's topic, `_values`): MQTT 5 message expiry applies to it
    /// (ClientOptions::message_expiry), never to `_status`, `_meta` or results.
    bool live : 1 = false;
    /// MQTT 5 content type `text/plain` rather than `application/json`
    /// (ClientOptions::describe_payloads): a payload that is not JSON.
    bool text : 1 = false;
    /// MQTT 5 correlation data (binary), for a write result sent to a request's response topic.
    std::string correlation_data;
    /// MQTT 5 user properties, each name and value followed by a NUL (`unit\0rpm\0`): what
    /// mqtt.properties chose of a data message's tag (add_user_property).
    std::string user_properties;
    /// Non-zero: once the broker acknowledged it (QoS 1 PUBACK; QoS 0: once written), the
    /// client hands this token to its on_acknowledged handler (store-and-forward deletes a
    /// journal entry only then).
    std::uint64_t ack_token = 0;

    /// Blank again, as a default Message, but the strings keep their buffers: a message is
    /// filled again instead of allocated anew for every publication.
    void clear() {
        topic.clear();
        payload.clear();
        correlation_data.clear();
        user_properties.clear();
        qos = 0;
        retain = false;
        coalesce = true;
        batch_lane = false;
        ack_token = 0;
        historical = false;
        live = false;
        text = false;
    }
};

/// Appends one user property to `message` (names and values hold no NUL: they are the
/// configuration's and the gateway's own texts).
inline void add_user_property(Message& message, std::string_view name, std::string_view value) {
    message.user_properties.append(name).push_back('\0');
    message.user_properties.append(value).push_back('\0');
}

// The six flags share the int's 8 bytes: 144 bytes a message, not more with a flag between
// strings, and a queue holds one per topic (its memory under overload stays bounded).
static_assert(sizeof(Message) <= 4 * sizeof(std::string) + 16);

/// MQTT's own limit on a packet's size: a remaining length of at most 268,435,455 bytes after a
/// fixed header of at most 5. A broker may announce a lower one (MQTT 5 CONNACK's Maximum Packet
/// Size) and closes the connection on a packet over it.
inline constexpr std::size_t max_mqtt_packet_bytes = 268435455 + 5;

/// The most bytes the PUBLISH packet of `message` can take: its topic, payload and correlation
/// data, plus a fixed header (5), the topic's length (2), a packet id (2), the properties'
/// length (4) and the correlation data's identifier and length (3), and each user property's
/// identifier and two lengths (at most its two texts' bytes again). What a broker's Maximum
/// Packet Size is held against (a client that describes its payloads keeps room for that:
/// described_payload_bytes).
inline std::size_t publish_packet_bytes(const Message& message) {
    constexpr std::size_t overhead = 5 + 2 + 2 + 4 + 3;
    return overhead + message.topic.size() + message.payload.size() +
           message.correlation_data.size() + 2 * message.user_properties.size();
}

/// The most bytes ClientOptions::describe_payloads and message_expiry add to a PUBLISH: content
/// type (1 + 2 + 16), payload format indicator (2), message expiry (5) and a topic alias (3).
inline constexpr std::size_t described_payload_bytes = 29;

/// A message received on a subscription, copied off Paho's thread.
struct Incoming {
    std::string topic;
    std::string payload;
    bool retained = false;
    std::string response_topic;          ///< MQTT 5 request/response; empty when absent
    std::string correlation_data;        ///< MQTT 5; binary, may be empty
    std::int64_t message_expiry_s = -1;  ///< MQTT 5 message expiry interval; -1 when absent
};

}  // namespace eip2mqtt::adapters::mqtt
