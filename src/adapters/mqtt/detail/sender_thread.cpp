// The Sender's thread: takes bursts from the ledger, builds Paho's messages without the lock,
// and hands them to Paho.

#include <malloc.h>
#include <pthread.h>

#include "adapters/mqtt/detail/publication_check.hpp"
#include "adapters/mqtt/detail/sender.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace {

/// Queued publications past which the memory of a drained backlog is given back (malloc_trim
/// walks every arena: worth it after a burst, not after every message).
constexpr std::size_t kTrimAfterBacklog = 10000;

}  // namespace

bool Sender::ready_to_send() const {
    return !quit_ && sending_ && link_up_.load(std::memory_order_relaxed) &&
           ledger_.ready_to_send();
}

void Sender::sender_main() {
    // Named for `top -H` and profiles (at most 15 characters).
    ::pthread_setname_np(::pthread_self(), "mqtt-sender");
    std::vector<Taken> taken;
    std::vector<Outgoing> burst;
    std::unique_lock lock(mutex_);
    for (;;) {
        sender_idle_ = true;
        if (idle_wanted_) completed_.notify_all();
        wake_sender_.wait(lock, [this] { return quit_ || ready_to_send(); });
        sender_idle_ = false;
        if (quit_) {
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
            discarded_.fetch_add(1, std::memory_order_relaxed);
            ledger_.drop_taken(std::move(next.message));
            taken.pop_back();
            if (stopping_) completed_.notify_all();  // no longer pending: stop() may be done
            continue;
        }
        if (next.probe) return;  // a suspect goes alone
    }
}

void Sender::prepare_burst(std::vector<Taken>& taken) {
    const std::size_t max_packet_size = max_packet_size_;
    for (auto& next : taken) {
        if (auto problem = publication_problem(next.message, max_packet_size); !problem.empty()) {
            refused_.fetch_add(1, std::memory_order_relaxed);
            log_refused(next.message.topic, problem);
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
            if (stopping_) completed_.notify_all();  // no longer pending: stop() may be done
            continue;
        }
        const auto id = ledger_.admit(std::move(next.message), next.probe);
        burst.push_back({id, std::move(next.out)});
    }
    taken.clear();
    return ledger_.end_burst();
}

::mqtt::message_ptr Sender::to_paho(const Message& message) const {
    auto out = ::mqtt::make_message(message.topic, message.payload, message.qos, message.retain);
    if (options_.version == 5 && (!message.correlation_data.empty() || message.historical)) {
        ::mqtt::properties properties;
        if (!message.correlation_data.empty()) {
            properties.add({::mqtt::property::CORRELATION_DATA, message.correlation_data});
        }
        if (message.historical) {
            properties.add({::mqtt::property::USER_PROPERTY, "historical", "true"});
        }
        out->set_properties(std::move(properties));
    }
    return out;
}

void Sender::send(std::uint64_t id, const ::mqtt::message_ptr& message) {
    try {
        paho_.publish(message, to_context(id), publish_listener_);
    } catch (const ::mqtt::exception& e) {
        on_send_refused(id, message, e);
    }
}

void Sender::on_send_refused(std::uint64_t id, const ::mqtt::message_ptr& message,
                             const ::mqtt::exception& e) {
    std::unique_lock lock(mutex_);
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
            completed_.notify_all();
            log_dropped_suspect(dropped);
        }
        return;
    }
    ledger_.settle(id);
    publish_failures_.fetch_add(1, std::memory_order_relaxed);
    lock.unlock();
    completed_.notify_all();
    log_publish_failure(message->get_topic(), e.what());
}

}  // namespace eip2mqtt::adapters::mqtt::detail
