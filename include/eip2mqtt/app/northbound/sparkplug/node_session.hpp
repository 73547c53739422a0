#pragma once
/// The edge node's session with its broker (docs/sparkplug.md): the bdSeq of each connection's
/// will, whether the node may publish (connected, and its primary host online when it has one),
/// whether it is born, and when a birth may start. A birth waits for the broker's
/// acknowledgement of the NDEATH said on this connection (or death_acknowledgement_timeout),
/// and a rebirth asked for while one is in progress (rebirth_hold) is pending until it ends.
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

/// How long a rebirth stays in progress: requests meanwhile (NCMD, the primary host back
/// online) make one pending rebirth, done when it ends. A flood of requests costs one rebirth
/// a second, not one each.
inline constexpr std::chrono::seconds rebirth_hold{1};

/// How long births wait for the broker's acknowledgement of the NDEATH before them: a broker
/// that never answers it must not keep the node from being born for good.
inline constexpr std::chrono::seconds death_acknowledgement_timeout{10};

/// Set in every ack_token the node gives its own publications, never in a journal entry's id
/// (SQLite row ids stay below 2^63): one acknowledgement handler tells them apart.
inline constexpr std::uint64_t sparkplug_own_token = std::uint64_t{1} << 63;

class NodeSession {
public:
    /// `death_topic`: the node's NDEATH topic; `primary_host`: births wait for its STATE.
    NodeSession(std::string death_topic, bool primary_host);

    /// The bdSeq of the next CONNECT's will: each connection made takes the next one (0-255,
    /// then 0 again); an attempt that made none leaves it as it was.
    std::uint8_t next_will();
    /// A pair's leader opens the session: the next will takes one more than `heard`
    /// (core/redundancy/bd_seq.hpp).
    void begin_session(std::optional<std::uint8_t> heard);
    /// The session ended (a leader stepped down): nothing is published until the next
    /// connection's births.
    void end_session();
    std::optional<std::uint8_t> session_bd_seq() const {
        return session_open_ ? std::optional<std::uint8_t>(bd_seq_) : std::nullopt;
    }
    std::uint8_t bd_seq() const { return bd_seq_; }
    /// The NDEATH of the current bdSeq, stamped `wall_ms`, QoS 1, no ack_token.
    adapters::mqtt::Message death_message(std::int64_t wall_ms) const;

    /// The connection is up: not born, the host's STATE to come again, nothing waiting.
    void connected();
    bool may_publish() const { return connected_ && (!primary_host_ || host_online_); }
    bool host_online() const { return host_online_; }
    /// The primary host's STATE changed; offline cancels a pending rebirth.
    void set_host_online(bool online);
    bool born() const { return born_; }
    void set_born() { born_ = true; }

    /// The gateway's tick.
    void tick(core::MonoTime now) { now_ = now; }
    core::MonoTime now() const { return now_; }

    /// A rebirth asked for: true when it may start now; else it is pending (birth_due()).
    bool request_birth();
    /// A pending rebirth may start now.
    bool birth_due() const { return rebirth_pending_ && birth_may_start(); }
    /// What begin_birth() decided.
    enum class BirthStart {
        refused,  ///< the node may not publish: no birth
        started,
        /// started without the broker's acknowledgement of the last NDEATH, at its deadline
        started_unacknowledged,
    };
    /// A birth begins now (not born until set_born()); a rebirth in progress until rebirth_hold
    /// has passed. Ends a pending one.
    BirthStart begin_birth();
    /// The NDEATH said now on this connection, carrying the returned ack_token: not born, and no
    /// birth before the broker acknowledges it (or death_acknowledgement_timeout).
    std::uint64_t death_said();
    /// What an acknowledgement meant to the session.
    enum class Acknowledged {
        not_ours,  ///< another owner's token (a journal entry's)
        ours,
        birth_due,  ///< the NDEATH births waited for: a pending rebirth may start now
    };
    Acknowledged acknowledged(std::uint64_t ack_token);

private:
    bool birth_may_start() const;

    std::string death_topic_;
    bool primary_host_;
    bool connected_ = false;
    bool host_online_ = false;
    bool born_ = false;        ///< NBIRTH sent on this connection, host online
    std::uint8_t bd_seq_ = 0;  ///< of the current connection's will
    std::uint8_t next_bd_seq_ = 0;
    bool will_connected_ = true;  ///< the last will's CONNECT made a connection
    bool session_open_ = false;   ///< a will was made since the last end_session()
    /// The NDEATH said on this connection and not yet acknowledged: no birth before it is.
    std::uint64_t death_unacknowledged_ = 0;
    core::MonoTime death_deadline_{};  ///< births go on without the acknowledgement then
    std::uint64_t next_ack_token_ = 0;
    bool rebirth_pending_ = false;
    core::MonoTime now_{};               ///< of the last tick
    core::MonoTime birth_hold_until_{};  ///< a rebirth is in progress until then
};

}  // namespace eip2mqtt::app::northbound::sparkplug
