#pragma once
/// The sender's bookkeeping: what waits (the Outbox, and the publications to send again), what
/// is in flight (the InFlightWindow), and the rules that decide what may go next: the two
/// windows of detail/send_room.hpp, a suspect sent alone, the hold after a loss, and the slots
/// the client's own publications take. It answers; the Sender acts (calls Paho, counts, logs).
///
/// Retries: a publication in flight when the connection went is a suspect, since the broker
/// may have closed the connection on it. It goes again after the reconnect, alone; in flight
/// alone when the connection goes again, it is dropped. One that never left (Paho refused it,
/// disconnected) goes again as what it was. Retries go before anything queued, by original id.
///
/// Module-private (src/adapters/mqtt/detail); pure (no Paho, thread or clock) and not
/// thread-safe: the Sender holds its mutex around every call.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "adapters/mqtt/detail/in_flight_window.hpp"
#include "adapters/mqtt/detail/outbox.hpp"
#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class SendLedger {
public:
    /// `max_in_flight`: publications in flight at any QoS (at least 1); the acknowledged window
    /// starts at the same until set_acknowledged_limit.
    SendLedger(std::size_t capacity, std::size_t batch_capacity, bool batch_first,
               std::size_t max_in_flight);

    // --- what waits ------------------------------------------------------------------------
    /// Queues `message` in its lane (Outbox::push: leaves it blank, with buffers to fill).
    void push(Message& message) { outbox_.push(message); }
    /// Keeps the buffers of a publication done with, a window's worth at most.
    void recycle(Message&& message) { outbox_.recycle(std::move(message), in_flight_limit_); }
    bool has_queued() const { return !retry_.empty() || !outbox_.empty(); }
    /// Waiting in the lanes or to be sent again.
    std::size_t queued() const { return outbox_.size() + retry_.size(); }
    /// Drops what waits, retries included (the connection of a session-bound client went);
    /// returns how many.
    std::size_t discard_queued();
    /// Outbox::release_after_backlog, once no retry waits either.
    bool release_after_backlog(std::size_t threshold) {
        return retry_.empty() && outbox_.release_after_backlog(threshold);
    }
    Outbox& outbox() { return outbox_; }
    const Outbox& outbox() const { return outbox_; }

    // --- the windows -----------------------------------------------------------------------
    /// In flight, with those taken for a burst and not yet admitted.
    std::size_t pending() const { return in_flight_.pending() + taking_; }
    /// Of pending(), those awaiting an acknowledgement (QoS >= 1).
    std::size_t pending_acknowledged() const {
        return in_flight_.pending_acknowledged() + taking_acknowledged_;
    }
    std::size_t in_flight_limit() const { return in_flight_limit_; }
    std::size_t acknowledged_limit() const { return acknowledged_limit_; }
    /// On each connect: the broker's Receive Maximum (65535 when it sent none) bounds the
    /// acknowledged window, never beyond max_in_flight nor below 1.
    void set_acknowledged_limit(std::size_t receive_maximum);
    /// Whether something waits that the windows have room for, and no suspect or hold stops it.
    bool ready_to_send() const;

    // --- one burst: take_next until false, admit or drop each taken, then end_burst -------
    /// Moves the next publication there is room for into `message`, counted as pending until
    /// admitted or dropped; false when none. `probe` says it is a suspect: it goes alone, so
    /// take no more.
    bool take_next(Message& message, bool& probe);
    /// A taken publication goes to Paho: it enters the window; returns its id.
    std::uint64_t admit(Message&& message, bool probe);
    /// A taken publication is not sent (a broker would refuse it): its buffers are kept.
    void drop_taken(Message&& message);
    /// Ends the burst; returns whether the sender has a backlog to pack into full segments: the
    /// window full with more waiting, or a saturated connection (send_room.hpp).
    bool end_burst();
    /// Whether a backlog bound by the acknowledged window outlasted kSaturatedWindows windows.
    bool saturated() const { return saturated_; }

    // --- what Paho tells -------------------------------------------------------------------
    /// Takes publication `id` out of the window; nullopt when it is no longer there (abandoned
    /// on a loss, or already completed), so that nothing is counted twice.
    std::optional<Message> complete(std::uint64_t id) { return in_flight_.complete(id); }
    /// Publication `id` is done for good (sent or failed): a suspect no longer.
    void settle(std::uint64_t id) {
        if (probe_ == id) probe_.reset();
    }
    /// Publication `id` failed the way a connection loss makes it fail: sent again as a
    /// suspect. When it was the suspect in flight alone, it is dropped instead: returns its
    /// topic (empty when queued again).
    std::string requeue_suspect(std::uint64_t id, Message&& message);
    /// Publication `id` never left (Paho refused it, disconnected): sent again as it was.
    void requeue_unsent(std::uint64_t id, Message&& message);
    /// Hands every publication in flight to `f(id, Message&&)`, in id order, and forgets them.
    template <class F>
    void abandon_in_flight(F&& f) {
        in_flight_.abandon_all(std::forward<F>(f));
    }

    // --- the hold after a loss-like failure ------------------------------------------------
    /// Nothing is sent until release_hold (the next connect, or a timeout); true when the hold
    /// begins with this call, false when it was already on.
    bool hold();
    void release_hold() { held_ = false; }

    // --- the client's own QoS >= 1 publications (online, offline) --------------------------
    /// A new connection: the own publications of earlier ones are answered there or never.
    void new_connection();
    /// Takes an acknowledged slot for an own publication; returns the connection's generation.
    std::uint64_t reserve_own_slot();
    /// Gives back a slot of connection `generation`; false when that connection is gone.
    bool release_own_slot(std::uint64_t generation);
    /// Whether the own publications' reserved slots fit in the acknowledged window now.
    bool own_slots_fit() const {
        return pending_acknowledged() + own_unacknowledged_ <= acknowledged_limit_;
    }

private:
    struct Retry {
        Message message;
        bool suspect = false;
    };

    /// A suspect goes alone: nothing else while one is in flight, and one waits until nothing
    /// is in flight; nothing at all during a hold.
    bool suspect_waits() const {
        return probe_.has_value() || held_ ||
               (!retry_.empty() && retry_.begin()->second.suspect && pending() != 0);
    }
    /// Whether the next publication to take awaits an acknowledgement (QoS >= 1).
    bool next_awaits_ack() const;
    bool acknowledged_room() const;
    /// The wake-up rule: acknowledged_room, or has_saturated_room on a saturated connection.
    bool acknowledged_refill() const;
    /// A taken publication is no longer counted as taken.
    void untake(const Message& message);

    Outbox outbox_;
    std::map<std::uint64_t, Retry> retry_;  ///< by original id
    InFlightWindow<Message> in_flight_;
    std::optional<std::uint64_t> probe_;  ///< the suspect in flight, alone
    bool held_ = false;
    bool window_full_ = false;  ///< the last burst stopped at the limit: wait for the low mark
    std::size_t taking_ = 0;    ///< taken, neither admitted nor dropped yet
    std::size_t taking_acknowledged_ = 0;
    std::size_t admitted_ = 0;  ///< publications admitted since the connection started
    /// admitted_ when the current backlog bound by the acknowledged window began.
    std::optional<std::size_t> ack_backlog_since_;
    bool saturated_ = false;
    bool stopped_by_acknowledgements_ = false;  ///< the last take_next found the window full
    const std::size_t in_flight_limit_;
    std::size_t acknowledged_limit_;
    std::size_t own_unacknowledged_ = 0;
    std::uint64_t own_generation_ = 0;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
