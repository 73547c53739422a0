#include "adapters/mqtt/detail/send_ledger.hpp"

#include <algorithm>

#include "adapters/mqtt/detail/send_room.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

SendLedger::SendLedger(std::size_t capacity, std::size_t batch_capacity, bool batch_first,
                       std::size_t max_in_flight)
    : outbox_(capacity, batch_capacity, batch_first),
      in_flight_limit_(std::max<std::size_t>(1, max_in_flight)),
      acknowledged_limit_(in_flight_limit_) {}

std::size_t SendLedger::discard_queued() {
    const std::size_t count = outbox_.discard_all() + retry_.size();
    retry_.clear();
    return count;
}

void SendLedger::set_acknowledged_limit(std::size_t receive_maximum) {
    acknowledged_limit_ = std::max<std::size_t>(1, std::min(in_flight_limit_, receive_maximum));
}

bool SendLedger::next_awaits_ack() const {
    if (!retry_.empty()) return retry_.begin()->second.message.qos > 0;
    const Message* next = outbox_.peek_next();
    return next != nullptr && next->qos > 0;
}

bool SendLedger::acknowledged_room() const {
    return has_acknowledged_room(pending_acknowledged(), own_unacknowledged_, acknowledged_limit_);
}

bool SendLedger::acknowledged_refill() const {
    return saturated_ ? has_saturated_room(pending_acknowledged(), own_unacknowledged_,
                                           acknowledged_limit_)
                      : acknowledged_room();
}

bool SendLedger::ready_to_send() const {
    if (!has_queued() || suspect_waits()) return false;
    return has_room(pending(), in_flight_limit_, window_full_) &&
           (!next_awaits_ack() || acknowledged_refill());
}

bool SendLedger::take_next(Message& message, bool& probe) {
    stopped_by_acknowledgements_ = false;
    if (pending() >= in_flight_limit_ || suspect_waits()) return false;
    if (!acknowledged_room() && next_awaits_ack()) {
        stopped_by_acknowledgements_ = true;
        return false;
    }
    probe = false;
    if (!retry_.empty()) {
        auto retry = std::move(retry_.extract(retry_.begin()).mapped());
        message = std::move(retry.message);
        probe = retry.suspect;
    } else if (!outbox_.take_next(message)) {
        return false;
    }
    ++taking_;
    if (message.qos > 0) ++taking_acknowledged_;
    return true;
}

void SendLedger::untake(const Message& message) {
    --taking_;
    if (message.qos > 0) --taking_acknowledged_;
}

std::uint64_t SendLedger::admit(Message&& message, bool probe) {
    untake(message);
    const bool acknowledged = message.qos > 0;
    const auto id = in_flight_.add(std::move(message), acknowledged);
    ++admitted_;
    if (probe) probe_ = id;
    return id;
}

void SendLedger::drop_taken(Message&& message) {
    untake(message);
    recycle(std::move(message));
}

bool SendLedger::end_burst() {
    window_full_ = in_flight_.pending() >= in_flight_limit_;
    // Where the burst stopped, not the window now: PUBACKs that came in since have freed slots.
    if (!stopped_by_acknowledgements_) {
        ack_backlog_since_.reset();
        saturated_ = false;
    } else if (!ack_backlog_since_) {
        ack_backlog_since_ = admitted_;
    } else {
        saturated_ = admitted_ - *ack_backlog_since_ >= kSaturatedWindows * acknowledged_limit_;
    }
    return (window_full_ && has_queued()) || saturated_;
}

std::string SendLedger::requeue_suspect(std::uint64_t id, Message&& message) {
    if (probe_ == id) {
        // It went alone, on a connection made after it became a suspect, and the connection
        // went again: the broker refuses it. One retry is all it gets.
        probe_.reset();
        return std::move(message.topic);
    }
    retry_.emplace(id, Retry{std::move(message), true});
    return {};
}

void SendLedger::requeue_unsent(std::uint64_t id, Message&& message) {
    // Never left: it proved nothing. A suspect stays one, to be sent alone on the next
    // connection; demoted, it would go out with others and cost one more connection.
    const bool suspect = probe_ == id;
    if (suspect) probe_.reset();
    retry_.emplace(id, Retry{std::move(message), suspect});
}

bool SendLedger::hold() {
    if (held_) return false;  // once per loss, not once per abandoned publication
    held_ = true;
    return true;
}

void SendLedger::new_connection() {
    ack_backlog_since_.reset();
    saturated_ = false;
    own_unacknowledged_ = 0;
    ++own_generation_;
}

std::uint64_t SendLedger::reserve_own_slot() {
    ++own_unacknowledged_;
    return own_generation_;
}

bool SendLedger::release_own_slot(std::uint64_t generation) {
    // One of an earlier connection: new_connection started this one's count afresh.
    if (generation != own_generation_ || own_unacknowledged_ == 0) return false;
    --own_unacknowledged_;
    return true;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
