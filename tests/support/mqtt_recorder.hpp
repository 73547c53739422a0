#pragma once
/// A Paho subscriber that records everything it receives, for assertions in tests. Waiting is
/// event-driven: wait_for() blocks on a condition variable until a predicate over the
/// recorded messages holds, or the timeout passes.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::test {

struct Received {
    std::string topic;
    std::string payload;
    bool retained = false;
    /// A QoS 1 delivery the broker made again after the recorder's session resumed (DUP).
    bool duplicate = false;
    std::chrono::steady_clock::time_point at;
    /// MQTT 5 properties, when present.
    std::string correlation_data;
    std::vector<std::pair<std::string, std::string>> user_properties;
    std::string content_type;
    int payload_format = -1;             ///< the payload format indicator; -1 when absent
    std::int64_t message_expiry_s = -1;  ///< what the broker left of it; -1 when absent
};

/// A user name and password for brokers that want one (none when `username` is empty), and the
/// protocol version for those that speak no MQTT 5.
struct MqttLogin {
    std::string username;
    std::string password;
    int version = 5;  ///< 5, or 4: MQTT 3.1.1 (no properties, no retain handling)
};

class MqttRecorder {
public:
    /// Connects (MQTT 5, clean start) to `url` and subscribes to each filter at QoS 1;
    /// returns once subscribed.
    MqttRecorder(const std::string& url, const std::vector<std::string>& filters,
                 const std::string& client_id = "", const MqttLogin& login = {});
    ~MqttRecorder();

    using Predicate = std::function<bool(const std::vector<Received>&)>;
    /// True once `pred` holds over everything recorded so far; false after `timeout`.
    bool wait_for(const Predicate& pred,
                  std::chrono::milliseconds timeout = std::chrono::seconds(10));
    /// Waits for a message on `topic` whose payload satisfies `pred` (any payload when null);
    /// returns it, or nullopt after `timeout`. Only messages recorded after `from` count.
    std::optional<Received> wait_for_message(
        const std::string& topic, const std::function<bool(const std::string&)>& pred = nullptr,
        std::chrono::milliseconds timeout = std::chrono::seconds(10), std::size_t from = 0);

    std::vector<Received> messages() const;
    std::vector<Received> messages_on(const std::string& topic) const;
    std::size_t count() const;
    /// Connected to the broker now (it reconnects by itself after the broker was away).
    bool connected() const;
    /// The last message recorded on `topic`.
    std::optional<Received> last(const std::string& topic) const;

    /// Publishes from the recorder's own connection (QoS 1, waits for completion).
    void publish(const std::string& topic, const std::string& payload, bool retain = false);
    /// Publishes an MQTT 5 request: with a response topic and correlation data.
    void publish_request(const std::string& topic, const std::string& payload,
                         const std::string& response_topic, const std::string& correlation_data);
    /// Publishes (QoS 1, not retained) with an MQTT 5 message expiry interval: the broker
    /// discards the message if it cannot deliver it within `expiry`.
    void publish_with_expiry(const std::string& topic, const std::string& payload,
                             std::chrono::seconds expiry);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace eip2mqtt::test
