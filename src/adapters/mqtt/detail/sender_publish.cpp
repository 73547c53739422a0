// A publication's way through Paho: the sender's thread takes bursts from the ledger, builds
// Paho's messages without the lock and hands them over; Paho answers (completed, failed,
// refused); what a lost connection left in flight goes again.

#include <malloc.h>
#include <pthread.h>

#include <chrono>

#include "adapters/mqtt/detail/publication_check.hpp"
#include "adapters/mqtt/detail/sender.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace {

/// Queued publications past which the memory of a drained backlog is given back (malloc_trim
/// walks every arena: worth it after a burst, not after every message).
constexpr std::size_t kTrimAfterBacklog = 10000;

/// How long the thread holds after a loss-like failure if the connection does not go meanwhile.
constexpr auto kLossHold = std::chrono::seconds(1);

}  // namespace

// --- the thread ----------------------------------------------------------------------------

bool Sender::ready_to_send() const {
    return !signals_.quitting() && sending_ && link_up_.load(std::memory_order_relaxed) &&
           ledger_.ready_to_send();
}

void Sender::sender_main() {
    // Named for `top -H` and profiles (at most 15 characters).
    ::pthread_setname_np(::pthread_self(), "mqtt-sender");
    std::vector<Taken> taken;
    std::vector<Outgoing> burst;
    SenderSignals::Lock lock(mutex_);
    for (;;) {
        if (!signals_.sleep_until_ready(lock, [this] { return ready_to_send(); })) {
            return;
        }
        // The lock is held to move publications between queues, never to build Paho's
        // messages: Paho's send thread completes QoS 0 publications under its own mutex and
        // waits for ours, and every publish waits for Paho's.
        take_burst(taken);
        lock.unlock();
        prepare_burst(taken);
        lock.lock();
        // Nagle for a backlog that waits on the sending itself, and on a saturated connection
        // (SendLedger::saturated). A burst that waits for PUBACKs (the broker's Receive Maximum
        // reached) gains nothing from fuller segments, and against a broker that leaves Nagle
        // on too (Mosquitto's default) each side then holds its next segment until the other's
        // delayed ACK: 40 ms stalls in a latency tail. Saturated, the queue is the latency, and
        // a segment and two wake-ups per publication are what the connection cannot afford.
        const bool backlog = admit_burst(taken, burst);
        // A large backlog (the first publication of every tag, a reconnect's republish, an
        // outage's buffer) leaves its freed messages in malloc's arenas: once it has drained,
        // give them back, so that resident memory follows the live data.
        const bool trim = ledger_.release_after_backlog(kTrimAfterBacklog);
        lock.unlock();
        nagle_.set_backlogged(backlog);
        if (trim) {
            ::malloc_trim(0);
        }
        for (const auto& out : burst) {
            send(out.id, out.message);
        }
        burst.clear();
        lock.lock();
    }
}

void Sender::take_burst(std::vector<Taken>& taken) {
    for (;;) {
        Taken& next = taken.emplace_back();
        if (!ledger_.take_next(next.message, next.probe)) {
            taken.pop_back();
            return;
        }
        if (options_.may_send && !options_.may_send(next.message)) {
            SenderCounters::bump(counters_.discarded);
            ledger_.drop_taken(std::move(next.message));
            taken.pop_back();
            if (stopping_) signals_.completed();  // no longer pending: stop() may be done
            continue;
        }
        if (next.probe) return;  // a suspect goes alone
    }
}

void Sender::prepare_burst(std::vector<Taken>& taken) {
    // Room for what describing a payload adds (content type, expiry, an alias).
    const std::size_t described =
        options_.describe_payloads || options_.message_expiry.count() > 0 || options_.topic_aliases
            ? described_payload_bytes
            : 0;
    const std::size_t limit = max_packet_size_;
    const std::size_t max_packet_size = limit > described ? limit - described : 0;
    for (auto& next : taken) {
        if (auto problem = publication_problem(next.message, max_packet_size); !problem.empty()) {
            SenderCounters::bump(counters_.refused);
            log_.refused(next.message.topic, problem);
            continue;
        }
        // Paho copies topic and payload: the window keeps our Message only for a re-send.
        next.out = to_paho(next.message);
    }
}

bool Sender::admit_burst(std::vector<Taken>& taken, std::vector<Outgoing>& burst) {
    for (auto& next : taken) {
        if (!next.out) {
            ledger_.drop_taken(std::move(next.message));
            if (stopping_) signals_.completed();  // no longer pending: stop() may be done
            continue;
        }
        const auto id = ledger_.admit(std::move(next.message), next.probe);
        burst.push_back({id, std::move(next.out)});
    }
    taken.clear();
    return ledger_.end_burst();
}

::mqtt::message_ptr Sender::to_paho(const Message& message) { return properties_.to_paho(message); }

void Sender::send(std::uint64_t id, const ::mqtt::message_ptr& message) {
    try {
        paho_.publish(message, to_context(id), publish_listener_);
    } catch (const ::mqtt::exception& e) {
        on_send_refused(id, message, e);
    }
}

// --- what Paho answers ----------------------------------------------------------------------

void Sender::on_send_refused(std::uint64_t id, const ::mqtt::message_ptr& message,
                             const ::mqtt::exception& e) {
    SenderSignals::Lock lock(mutex_);
    auto item = ledger_.complete(id);
    if (!item) {
        return;  // abandoned meanwhile by on_connection_lost
    }
    if (e.get_return_code() == MQTTASYNC_DISCONNECTED) {
        // Never left: no duplicate possible.
        ledger_.requeue_unsent(id, std::move(*item));
        hold_for_reconnect();
        return;
    }
    if (requeue_in_flight_ && item->qos > 0 && !stopping_) {
        // Refused at once, most often because the connection is going: sent again, alone,
        // like a publication in flight at a connection loss; refused alone, it is dropped.
        auto dropped = requeue_after_loss(id, std::move(*item));
        lock.unlock();
        if (!dropped.empty()) {
            signals_.completed();
            log_.dropped_suspect(dropped);
        }
        return;
    }
    ledger_.settle(id);
    SenderCounters::bump(counters_.publish_failures);
    lock.unlock();
    signals_.completed();
    log_.publish_failure(message->get_topic(), e.what());
}

void Sender::PublishListener::on_success(const ::mqtt::token& tok) {
    sender_.on_publish_done(from_context(tok.get_user_context()), 0, 0, {});
}

void Sender::PublishListener::on_failure(const ::mqtt::token& tok) {
    sender_.on_publish_done(from_context(tok.get_user_context()),
                            tok.get_return_code() == 0 ? -1 : tok.get_return_code(),
                            tok.get_reason_code(), describe_failure(tok));
}

void Sender::on_publish_done(std::uint64_t id, int rc, int reason_code, const std::string& reason) {
    std::string failed_topic;
    std::string dropped_topic;
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        auto item = ledger_.complete(id);
        if (!item) {
            return;  // already re-queued or counted by on_connection_lost
        }
        if (rc == 0) {
            ledger_.settle(id);
            SenderCounters::bump(counters_.published);
            if (item->ack_token != 0) {
                loop_.post([this, token = item->ack_token] {
                    if (on_acknowledged_) on_acknowledged_(token);
                });
            }
            ledger_.recycle(std::move(*item));
        } else if (requeue_in_flight_ && item->qos > 0 && !stopping_ &&
                   !broker_refused(rc, reason_code)) {
            // No verdict of the broker's: failed because the connection went (Paho may report
            // that before its connection-lost handler runs). Sent again after the reconnect,
            // alone; a broker's refusal is final.
            dropped_topic = requeue_after_loss(id, std::move(*item));
        } else {
            ledger_.settle(id);
            SenderCounters::bump(counters_.publish_failures);
            failed_topic = std::move(item->topic);
        }
        wake = signals_.sleeping() && ready_to_send();
    }
    if (stopping_) {
        signals_.completed();
    }
    if (wake) {
        signals_.wake_one();
    }
    if (!failed_topic.empty()) {
        log_.publish_failure(failed_topic, reason);
    }
    if (!dropped_topic.empty()) {
        log_.dropped_suspect(dropped_topic);
    }
}

bool Sender::broker_refused(int rc, int reason_code) const {
    return options_.version == 5 && rc != MQTTASYNC_DISCONNECTED &&
           rc != MQTTASYNC_OPERATION_INCOMPLETE && link_up_ && reason_code >= 0x80 &&
           reason_code <= 0xA2;
}

// --- the requeue after a loss --------------------------------------------------------------

std::string Sender::requeue_after_loss(std::uint64_t id, Message&& message) {
    hold_for_reconnect();
    auto dropped = ledger_.requeue_suspect(id, std::move(message));
    if (!dropped.empty()) {
        SenderCounters::bump(counters_.refused);
    }
    return dropped;
}

void Sender::hold_for_reconnect() {
    if (!ledger_.hold()) return;
    loop_.post([this] {
        hold_timer_.expires_after(kLossHold);
        hold_timer_.async_wait(loop_.guarded([this](const boost::system::error_code& ec) {
            if (ec) return;
            {
                std::lock_guard lock(mutex_);
                ledger_.release_hold();
            }
            signals_.wake_all();
        }));
    });
}

}  // namespace eip2mqtt::adapters::mqtt::detail
