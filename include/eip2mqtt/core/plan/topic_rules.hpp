#pragma once
/// What an MQTT broker accepts as a topic name and as a UTF-8 string (MQTT 5 §1.5.4 and
/// §4.7): the gateway checks every name that ends up in a topic, and every topic it publishes,
/// against these rules, because a broker answers a publication it refuses by closing the
/// connection, and the gateway would then send it again after every reconnect.

#include <cstddef>
#include <string>
#include <string_view>

namespace eip2mqtt::core::plan {

/// MQTT encodes a topic's length in two bytes.
inline constexpr std::size_t max_topic_bytes = 65535;

/// Why `text` is not a UTF-8 string every broker accepts, or empty when it is. Refused:
/// invalid or overlong UTF-8, surrogates, U+0000, the control characters U+0001..U+001F and
/// U+007F..U+009F, and the non-characters (U+FDD0..U+FDEF, U+xFFFE, U+xFFFF). The MQTT
/// specification forbids the first three and lets a receiver refuse the others; Mosquitto
/// does, by closing the connection. Refused too, though brokers take them: the bidirectional
/// controls (U+061C, U+200E, U+200F, U+202A..U+202E, U+2066..U+2069), with which a topic or a
/// name reads, on a screen or in a log, as other than it is.
std::string_view text_problem(std::string_view text);

/// Why `topic` cannot be published to, or empty when it can: empty, longer than
/// max_topic_bytes, holding a wildcard ('+' or '#'), or failing text_problem().
std::string topic_name_problem(std::string_view topic);

}  // namespace eip2mqtt::core::plan
