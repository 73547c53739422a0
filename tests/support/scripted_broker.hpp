#pragma once
/// A TCP listener on a free loopback port that plays one exchange of MQTT packets per connection,
/// byte for byte: for the refusals and disconnects a real broker of another kind or version
/// sends (RabbitMQ 3.10 closing on an MQTT 5 CONNECT, a 3.1.1 CONNACK "unacceptable protocol
/// version", MQTT 5 reason 0x8E), which the gateway must name. Not a broker: it reads packets
/// only to know when to answer.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace eip2mqtt::test {

class ScriptedBroker {
public:
    /// On each connection: reads the CONNECT and sends `on_connect` (nothing: closes at once);
    /// then, when `after_next_packet` is not empty, reads the client's next packet (its first
    /// SUBSCRIBE or PUBLISH, sent once it saw the CONNACK) and sends `after_next_packet`. Then
    /// closes the connection.
    ScriptedBroker(std::vector<std::uint8_t> on_connect,
                   std::vector<std::uint8_t> after_next_packet = {});
    ~ScriptedBroker();
    ScriptedBroker(const ScriptedBroker&) = delete;
    ScriptedBroker& operator=(const ScriptedBroker&) = delete;

    std::uint16_t port() const { return port_; }
    std::string url() const { return "tcp://127.0.0.1:" + std::to_string(port_); }
    /// The protocol level of the last CONNECT read (4: MQTT 3.1.1, 5: MQTT 5), 0 before one.
    int protocol_level() const { return protocol_level_; }
    std::size_t connections() const { return connections_; }

private:
    void serve();
    void play(int connection);

    std::vector<std::uint8_t> on_connect_;
    std::vector<std::uint8_t> after_next_packet_;
    int listener_ = -1;
    std::uint16_t port_ = 0;
    std::atomic<int> protocol_level_{0};
    std::atomic<std::size_t> connections_{0};
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace eip2mqtt::test
