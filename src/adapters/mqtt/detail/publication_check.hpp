#pragma once
/// Whether a broker will take a publication: a broker answers one it refuses (a topic with a
/// wildcard or invalid UTF-8, a packet over its maximum size) by closing the connection, and
/// the publication, queued again, would close every connection after it.
///
/// Module-private (src/adapters/mqtt/detail).

#include <cstddef>
#include <string>

#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

inline constexpr std::size_t max_mqtt_packet_size = max_mqtt_packet_bytes;

/// Why `message` cannot be published to a broker that takes packets of at most
/// `max_packet_size` bytes (its CONNACK's Maximum Packet Size, else max_mqtt_packet_size),
/// or empty when it can.
std::string publication_problem(const Message& message, std::size_t max_packet_size);

}  // namespace eip2mqtt::adapters::mqtt::detail
