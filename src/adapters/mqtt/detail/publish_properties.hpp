#pragma once
/// The MQTT 5 properties of each publication (docs/mqtt-api.md, "MQTT 5 metadata"): correlation
/// data, the `historical` mark and the user properties a message carries, the content type and
/// payload format indicator of a client that describes its payloads, the expiry of live values,
/// and topic aliases, assigned to live values per connection up to the broker's Topic Alias
/// Maximum.

#include <mqtt/message.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

/// The availability's `online` or `offline`: text, said so when the client describes its
/// payloads (ClientOptions::describe_payloads, MQTT 5).
::mqtt::message_ptr availability_message(const ClientOptions& options, const std::string& text);

class PublishProperties {
public:
    explicit PublishProperties(const ClientOptions& options) : options_(options) {}

    /// A new connection, whose broker takes `alias_maximum` topic aliases (0: none): the
    /// aliases of the last one mean nothing on it. Any thread.
    void on_connected(std::uint16_t alias_maximum);

    /// The Paho message of `message`, with its properties. The sender's thread alone: an alias
    /// is given to a topic the first time it is sent on a connection (with its name), and then
    /// sent in its place.
    ::mqtt::message_ptr to_paho(const Message& message);

    /// Publications sent by alias, without their topic's name.
    std::uint64_t aliased() const { return aliased_.load(std::memory_order_relaxed); }

private:
    /// The alias to send `topic` with: its own, a new one while the broker takes more, or 0.
    std::uint16_t alias_of(const std::string& topic, bool& known);

    const ClientOptions& options_;
    std::atomic<std::uint32_t> connection_{0};
    std::atomic<std::uint16_t> alias_maximum_{0};
    std::uint32_t aliases_of_ = 0;  ///< the connection `aliases_` were given on
    std::unordered_map<std::string, std::uint16_t> aliases_;
    std::atomic<std::uint64_t> aliased_{0};
};

}  // namespace eip2mqtt::adapters::mqtt::detail
