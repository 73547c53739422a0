// The edge node's session: bdSeq across wills, connections and restarts, and when births may
// start.

#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"

#include <utility>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/core/redundancy/bd_seq.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

NodeSession::NodeSession(std::string death_topic, bool primary_host,
                         std::optional<std::uint8_t> last_bd_seq)
    : death_topic_(std::move(death_topic)),
      primary_host_(primary_host),
      // 255 is followed by 0.
      next_bd_seq_(last_bd_seq ? static_cast<std::uint8_t>(*last_bd_seq + 1) : 0) {}

std::uint8_t NodeSession::next_will() {
    // A CONNECT that made no connection registered no will a host could have seen: its bdSeq
    // goes with the next attempt, so that an outage does not move it by one per attempt.
    if (will_connected_) {
        bd_seq_ = next_bd_seq_++;  // 255 is followed by 0
        will_connected_ = false;
    }
    session_open_ = true;
    return bd_seq_;
}

void NodeSession::begin_session(std::optional<std::uint8_t> heard) {
    next_bd_seq_ = core::redundancy::next_session_bd_seq(heard, next_bd_seq_);
    will_connected_ = true;  // taken by the next will, whatever became of the last CONNECT
}

void NodeSession::end_session() {
    left();
    session_open_ = false;
    host_online_ = false;
}

adapters::mqtt::Message NodeSession::death_message(std::int64_t wall_ms) const {
    adapters::sparkplug::Payload death;
    death.timestamp_ms = static_cast<std::uint64_t>(wall_ms);
    death.metrics.push_back({"bdSeq",
                             std::nullopt,
                             death.timestamp_ms,
                             adapters::sparkplug::DataType::int64,
                             core::plan::Value{std::int64_t{bd_seq_}},
                             false,
                             {}});
    adapters::mqtt::Message message;
    message.topic = death_topic_;
    message.payload = adapters::sparkplug::encode(death);
    message.qos = 1;  // the specification's: a host must learn of the death
    message.retain = false;
    message.coalesce = false;
    return message;
}

void NodeSession::connected() {
    connected_ = true;
    will_connected_ = true;
    born_ = false;
    rebirth_pending_ = false;
    // Whatever the host said before this connection may be old: its retained STATE comes
    // again right after our SUBSCRIBE, and births wait for it.
    host_online_ = false;
}

void NodeSession::set_host_online(bool online) {
    host_online_ = online;
    if (online) return;
    born_ = false;
    rebirth_pending_ = false;
}

bool NodeSession::request_birth() {
    if (birth_may_start()) return true;
    rebirth_pending_ = true;
    return false;
}

bool NodeSession::begin_birth(bool requested) {
    rebirth_pending_ = false;
    if (!may_publish()) return false;
    if (requested) birth_hold_until_ = now_ + rebirth_hold;
    born_ = false;
    return true;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
