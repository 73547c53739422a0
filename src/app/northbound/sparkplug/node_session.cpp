// The edge node's session: bdSeq across wills and connections, and the rules that order births
// after the NDEATH they follow.

#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"

#include <utility>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"
#include "eip2mqtt/core/redundancy/bd_seq.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

NodeSession::NodeSession(std::string death_topic, bool primary_host)
    : death_topic_(std::move(death_topic)), primary_host_(primary_host) {}

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
    connected_ = false;
    born_ = false;
    session_open_ = false;
    host_online_ = false;
    rebirth_pending_ = false;
    death_unacknowledged_ = 0;
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
    // What waited on the last connection is moot: its NDEATH was answered or went with it (the
    // will said it then), and this connection's births come now or with the host's STATE.
    death_unacknowledged_ = 0;
    rebirth_pending_ = false;
    // Whatever the host said before this connection may be old: its retained STATE comes
    // again right after our SUBSCRIBE, and births wait for it.
    host_online_ = false;
}

void NodeSession::set_host_online(bool online) {
    host_online_ = online;
    if (!online) rebirth_pending_ = false;
}

bool NodeSession::birth_may_start() const {
    // A host takes an NDEATH carrying the current NBIRTH's bdSeq for the node's death, and on
    // one connection every NBIRTH has the same bdSeq: an NDEATH overtaken by the next NBIRTH
    // would leave the node dead. The NDEATH is QoS 1 and births may be QoS 0, which MQTT does
    // not keep in order with it: births wait for its PUBACK.
    const bool death_settled = death_unacknowledged_ == 0 || now_ >= death_deadline_;
    return may_publish() && death_settled && now_ >= birth_hold_until_;
}

bool NodeSession::request_birth() {
    if (birth_may_start()) return true;
    rebirth_pending_ = true;
    return false;
}

NodeSession::BirthStart NodeSession::begin_birth() {
    rebirth_pending_ = false;
    if (!may_publish()) return BirthStart::refused;
    // birth_may_start() let it go at the deadline when the NDEATH is still unacknowledged: a
    // host may see this NBIRTH before the NDEATH, and take the node for dead.
    const bool unacknowledged = death_unacknowledged_ != 0;
    death_unacknowledged_ = 0;
    // In progress from now: another request waits for the hold to end.
    birth_hold_until_ = now_ + rebirth_hold;
    born_ = false;
    return unacknowledged ? BirthStart::started_unacknowledged : BirthStart::started;
}

std::uint64_t NodeSession::death_said() {
    death_unacknowledged_ = sparkplug_own_token | ++next_ack_token_;
    death_deadline_ = now_ + death_acknowledgement_timeout;
    born_ = false;
    return death_unacknowledged_;
}

NodeSession::Acknowledged NodeSession::acknowledged(std::uint64_t ack_token) {
    if ((ack_token & sparkplug_own_token) == 0) return Acknowledged::not_ours;
    // Not the one births wait for: an NDEATH of an earlier connection.
    if (ack_token != death_unacknowledged_) return Acknowledged::ours;
    death_unacknowledged_ = 0;
    return birth_due() ? Acknowledged::birth_due : Acknowledged::ours;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
