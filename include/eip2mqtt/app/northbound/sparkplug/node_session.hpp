#pragma once
/// The edge node's session with its broker (docs/sparkplug.md): the bdSeq of each connection's
/// will, whether the node may publish (connected, and its primary host online when it has one),
/// whether it is born, and when a birth may start. A host's rebirth request is answered at once;
/// the requests that follow it within rebirth_hold share one rebirth at the hold's end, and no
/// DATA goes out while one waits (Sparkplug B 3.0: DATA stops at a request).
///
/// Pure: time is what the last tick() said; the caller publishes what it is told to.
/// Threading: the loop only.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::northbound::sparkplug {

/// After a rebirth a host asked for, how long further requests wait for one rebirth together:
/// a flood of them costs a rebirth a second, not one each.
inline constexpr std::chrono::seconds rebirth_hold{1};

class NodeSession {
public:
    /// `death_topic`: the node's NDEATH topic; `primary_host`: births wait for its STATE;
    /// `last_bd_seq`: the bdSeq of the last will before this process (its state directory), so
    /// that the first will takes the one after it.
    NodeSession(std::string death_topic, bool primary_host,
                std::optional<std::uint8_t> last_bd_seq = std::nullopt);

    /// The bdSeq of the next CONNECT's will: each connection made takes the next one (0-255,
    /// then 0 again); an attempt that made none leaves it as it was.
    std::uint8_t next_will();
    /// A pair's leader opens the session: the next will takes one more than `heard`
    /// (core/redundancy/bd_seq.hpp).
    void begin_session(std::optional<std::uint8_t> heard);
    /// The session ended (a leader stepped down, or the node left its broker): nothing is
    /// published until the next connection's births.
    void end_session();
    std::optional<std::uint8_t> session_bd_seq() const {
        return session_open_ ? std::optional<std::uint8_t>(bd_seq_) : std::nullopt;
    }
    std::uint8_t bd_seq() const { return bd_seq_; }
    /// The NDEATH of the current bdSeq, stamped `wall_ms`, QoS 1, no ack_token.
    adapters::mqtt::Message death_message(std::int64_t wall_ms) const;

    /// The connection is up: not born, the host's STATE to come again, nothing waiting.
    void connected();
    /// The node leaves its connection (the primary host went offline): nothing is published
    /// until the next one's births, whatever the old one still hands it meanwhile.
    void left() {
        connected_ = false;
        born_ = false;
        rebirth_pending_ = false;
    }
    bool may_publish() const { return connected_ && (!primary_host_ || host_online_); }
    bool host_online() const { return host_online_; }
    /// The primary host's STATE changed; offline ends the node's births and a waiting rebirth.
    void set_host_online(bool online);
    bool born() const { return born_; }
    void set_born() { born_ = true; }
    /// DDATA and NDATA may go out: born, and no rebirth waits.
    bool may_send_data() const { return born_ && !rebirth_pending_; }

    /// The gateway's tick.
    void tick(core::MonoTime now) { now_ = now; }
    core::MonoTime now() const { return now_; }

    /// A host asked for a rebirth: true when it starts now (begin_birth(true)); else it waits
    /// for the hold's end (birth_due()), and DATA with it.
    bool request_birth();
    /// A waiting rebirth may start now.
    bool birth_due() const { return rebirth_pending_ && birth_may_start(); }
    /// A birth begins now (not born until set_born()); false when the node may not publish.
    /// `requested`: a host asked for it, and requests until rebirth_hold has passed wait.
    bool begin_birth(bool requested);

private:
    bool birth_may_start() const { return may_publish() && now_ >= birth_hold_until_; }

    std::string death_topic_;
    bool primary_host_;
    bool connected_ = false;
    bool host_online_ = false;
    bool born_ = false;        ///< NBIRTH sent on this connection, host online
    std::uint8_t bd_seq_ = 0;  ///< of the current connection's will
    std::uint8_t next_bd_seq_ = 0;
    bool will_connected_ = true;  ///< the last will's CONNECT made a connection
    bool session_open_ = false;   ///< a will was made since the last end_session()
    bool rebirth_pending_ = false;
    core::MonoTime now_{};               ///< of the last tick
    core::MonoTime birth_hold_until_{};  ///< requests wait until then
};

}  // namespace eip2mqtt::app::northbound::sparkplug
