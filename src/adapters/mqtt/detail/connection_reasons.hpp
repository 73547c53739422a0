#pragma once
/// Why the broker refused or ended a connection, in words an operator can act on: the MQTT 5
/// reason codes that name a cause outside the gateway (another client with our client id, a
/// broker that speaks only MQTT 3.1.1), and the pattern a broker that gives no reason leaves.
///
/// Module-private (src/adapters/mqtt/detail); pure: Paho's texts and the times are passed in.

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace eip2mqtt::adapters::mqtt::detail {

/// MQTT 5 §3.14.2.1: another connection with the same client id took the session over.
inline constexpr int kSessionTakenOver = 0x8E;
/// MQTT 5 CONNACK: the broker does not accept this protocol version.
inline constexpr int kUnsupportedProtocolVersion = 0x84;

/// The cause of a DISCONNECT with `reason_code` (MQTT 5), `reason_text` being Paho's words for it.
std::string describe_disconnect(int reason_code, std::string_view reason_text,
                                std::string_view client_id);

/// When a failed MQTT 5 connect shows a broker that does not speak MQTT 5, the explanation to
/// add to `failure` (Paho's description, with its message): a connection closed on our CONNECT
/// without a CONNACK (RabbitMQ before 3.13; over `tls` only a possibility, since a broker that
/// wants a client certificate closes the same way), a 3.1.1 CONNACK "unacceptable protocol
/// version" (return code 1), or reason 0x84. nullopt otherwise.
std::optional<std::string> mqtt5_refusal(int return_code, std::string_view failure, bool tls);

/// Counts the connections a broker closed without a reason soon after they were made. A broker
/// that sends no reason code 0x8E (Mosquitto before 2.0.15) ends the older of two connections
/// with one client id silently; two clients with one id then take turns, each connection
/// closing a moment after the other's reconnect. Not thread-safe: the client's loop owns it.
class SilentLossPattern {
public:
    static constexpr std::size_t kLossesInARow = 3;
    static constexpr std::chrono::seconds kShortLived{30};

    /// A connection that lived `lived` was lost, `silent` when no reason came with the loss.
    /// Returns whether the last kLossesInARow losses were all silent and short-lived.
    bool on_loss(bool silent, std::chrono::steady_clock::duration lived);

    /// The explanation for a silent loss that completes the pattern.
    static std::string explain(std::string_view client_id);

private:
    std::size_t in_a_row_ = 0;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
