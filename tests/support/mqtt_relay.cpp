// The recording MQTT relay: a TcpProxy whose tap reads each direction's bytes as MQTT packets.

#include "tests/support/mqtt_relay.hpp"

namespace eip2mqtt::test {

MqttRelay::MqttRelay(std::uint16_t broker_port, std::size_t id)
    : id_(id),
      proxy_(broker_port,
             [this](std::size_t link, TcpProxy::Direction direction, std::string_view bytes,
                    bool closed) { on_bytes(link, direction, bytes, closed); }) {}

void MqttRelay::on_bytes(std::size_t link, TcpProxy::Direction direction, std::string_view bytes,
                         bool closed) {
    {
        std::lock_guard lock(mutex_);
        const auto now = std::chrono::steady_clock::now();
        if (closed) {
            events_.push_back({link, direction, std::nullopt, id_, now});
        } else {
            auto& readers = readers_[link];
            const auto side = static_cast<std::size_t>(direction);
            for (auto& packet : readers[side].feed(bytes)) {
                // The broker's packets are read at the level the client's CONNECT asked for.
                if (packet.type == PacketType::connect) {
                    readers[1 - side].set_protocol_level(packet.protocol_level);
                }
                events_.push_back({link, direction, std::move(packet), id_, now});
            }
        }
    }
    changed_.notify_all();
}

MqttRelay::Events MqttRelay::events() const {
    std::lock_guard lock(mutex_);
    return events_;
}

bool MqttRelay::wait_for(const std::function<bool(const Events&)>& done,
                         std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return done(events_); });
}

}  // namespace eip2mqtt::test
