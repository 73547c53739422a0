#pragma once
/// The edge node's publications in `seq` order (docs/sparkplug.md): each message published
/// takes the next seq (0-255, then 0 again; an NBIRTH starts again at 0), and none goes out
/// that the broker would refuse (over its Maximum Packet Size, or `max_packet_bytes`), so that
/// a host never sees a gap in seq. Reuses one message buffer: publishing does not allocate
/// beyond the encoding.
///
/// Threading: the loop only.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

class SeqPublisher {
public:
    /// `mqtt` (the node's connection) and `clock` (the payloads' timestamps) must outlive it.
    /// `max_packet_bytes`: the largest PUBLISH packet to send, below the broker's own limit
    /// (0: the broker's alone). Every message goes at QoS 0, retain off: Sparkplug B 3.0's rule
    /// for births, data and deaths of devices.
    SeqPublisher(adapters::mqtt::Publisher& mqtt, const core::Clock& clock,
                 std::size_t max_packet_bytes);

    /// A connection to a broker taking packets of up to `broker_max_packet_bytes`.
    void connected(std::size_t broker_max_packet_bytes);
    /// The next message is seq 0 (an NBIRTH).
    void restart_seq() { seq_ = 0; }
    /// Publishes `payload` on `topic`, stamped now with the next seq and carrying `ack_token`
    /// (0: none); false, with nothing published and seq unchanged, when it is over the largest
    /// packet the broker takes.
    bool publish(const std::string& topic, adapters::sparkplug::Payload& payload,
                 std::uint64_t ack_token = 0);
    /// Publishes `message` as it is, outside seq (the NDEATH).
    void publish_unsequenced(adapters::mqtt::Message&& message) {
        mqtt_.publish(std::move(message));
    }

    /// The size of the last message publish() was given, for the log of a refused one.
    std::size_t last_packet_bytes() const { return last_packet_bytes_; }
    std::size_t max_packet_bytes() const { return max_packet_bytes_; }
    /// `max_packet_bytes` was configured (not 0).
    bool limit_configured() const { return configured_max_packet_bytes_ != 0; }

private:
    adapters::mqtt::Publisher& mqtt_;
    const core::Clock& clock_;
    std::size_t configured_max_packet_bytes_;
    std::size_t max_packet_bytes_ = adapters::mqtt::max_mqtt_packet_bytes;
    std::size_t last_packet_bytes_ = 0;
    std::uint8_t seq_ = 0;  ///< of the next message to publish
    adapters::mqtt::Message message_;
};

}  // namespace eip2mqtt::app::northbound::sparkplug
