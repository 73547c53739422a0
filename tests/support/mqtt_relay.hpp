#pragma once
/// An MQTT relay between a client and its broker that records every control packet either side
/// sends and every close, in order, for conformance checks that judge a client by what it put
/// on the wire (its CONNECT's will, each PUBLISH's QoS and retain, its DISCONNECT's reason code)
/// rather than by what a subscriber is handed. A TcpProxy underneath: it can be stalled or cut
/// as well. Thread-safe: the proxy's thread records, the test reads and waits.

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/mqtt_packets.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::test {

struct RelayEvent {
    std::size_t connection = 0;  ///< numbered from 0 in the order the relay took them
    /// to_server: the client sent it (or closed); to_client: the broker.
    TcpProxy::Direction direction = TcpProxy::Direction::to_server;
    std::optional<MqttPacket> packet;          ///< nullopt: the connection closed by that side
    std::size_t relay = 0;                     ///< which relay saw it, when several are merged
    std::chrono::steady_clock::time_point at;  ///< when the relay read it
    bool from_client() const { return direction == TcpProxy::Direction::to_server; }
    bool closed() const { return !packet.has_value(); }
};

class MqttRelay {
public:
    using Events = std::vector<RelayEvent>;

    /// Listens on an ephemeral loopback port; carries each connection to `broker_port`.
    /// `id`: written in each event's `relay`.
    explicit MqttRelay(std::uint16_t broker_port, std::size_t id = 0);
    MqttRelay(const MqttRelay&) = delete;
    MqttRelay& operator=(const MqttRelay&) = delete;

    std::uint16_t port() const { return proxy_.port(); }
    std::string url() const { return "tcp://127.0.0.1:" + std::to_string(port()); }
    TcpProxy& proxy() { return proxy_; }

    /// What was recorded so far.
    Events events() const;
    /// Waits until `done` holds over what was recorded, at most `timeout`.
    bool wait_for(const std::function<bool(const Events&)>& done,
                  std::chrono::milliseconds timeout = std::chrono::seconds(20)) const;

private:
    void on_bytes(std::size_t link, TcpProxy::Direction direction, std::string_view bytes,
                  bool closed);

    std::size_t id_;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    Events events_;
    /// Per connection, a reader per direction (to_server, to_client).
    std::map<std::size_t, std::array<MqttStreamReader, 2>> readers_;
    TcpProxy proxy_;  ///< last: its thread records into what is above
};

}  // namespace eip2mqtt::test
