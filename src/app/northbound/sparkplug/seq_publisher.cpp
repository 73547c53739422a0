// The edge node's publications: seq, the packet size limit, one reused message.

#include "eip2mqtt/app/northbound/sparkplug/seq_publisher.hpp"

#include <algorithm>
#include <utility>

namespace eip2mqtt::app::northbound::sparkplug {

SeqPublisher::SeqPublisher(adapters::mqtt::Publisher& mqtt, const core::Clock& clock,
                           std::size_t max_packet_bytes)
    : mqtt_(mqtt), clock_(clock), configured_max_packet_bytes_(max_packet_bytes) {}

void SeqPublisher::connected(std::size_t broker_max_packet_bytes) {
    max_packet_bytes_ = configured_max_packet_bytes_ == 0
                            ? broker_max_packet_bytes
                            : std::min(broker_max_packet_bytes, configured_max_packet_bytes_);
}

bool SeqPublisher::publish(const std::string& topic, adapters::sparkplug::Payload& payload,
                           std::uint64_t ack_token) {
    payload.timestamp_ms = static_cast<std::uint64_t>(clock_.wall_ms());
    payload.seq = seq_;
    message_.topic = topic;
    message_.payload = adapters::sparkplug::encode(payload);
    last_packet_bytes_ = adapters::mqtt::publish_packet_bytes(message_);
    if (last_packet_bytes_ > max_packet_bytes_) {
        // The client would drop it, and a host would see a gap in seq: it never leaves.
        message_.clear();
        return false;
    }
    seq_ = static_cast<std::uint8_t>(seq_ + 1);
    message_.qos = 0;
    message_.retain = false;
    // Every message counts in seq: none may replace another.
    message_.coalesce = false;
    message_.ack_token = ack_token;
    mqtt_.publish(std::move(message_));
    return true;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
