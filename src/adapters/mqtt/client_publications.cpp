// The publication side of Client::Impl: the queues, the sender thread that hands them to Paho,
// the in-flight window and what a connection loss does to it (suspects sent again alone).

#include <malloc.h>
#include <pthread.h>
#include <spdlog/spdlog.h>

#include "adapters/mqtt/detail/client_impl.hpp"
#include "adapters/mqtt/detail/send_room.hpp"

namespace eip2mqtt::adapters::mqtt {

using detail::kLossHold;
using detail::kTrimAfterBacklog;
using detail::to_context;

void Client::Impl::enqueue(Message& message) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        outbox_.push(message);
        wake = sender_idle_ && ready_to_send();
    }
    if (wake) {
        wake_sender_.notify_one();
    }
}

paho::message_ptr Client::Impl::to_paho(const Message& message) const {
    auto out = paho::make_message(message.topic, message.payload, message.qos, message.retain);
    if (options_.version == 5 && (!message.correlation_data.empty() || message.historical)) {
        paho::properties properties;
        if (!message.correlation_data.empty()) {
            properties.add({paho::property::CORRELATION_DATA, message.correlation_data});
        }
        if (message.historical) {
            properties.add({paho::property::USER_PROPERTY, "historical", "true"});
        }
        out->set_properties(std::move(properties));
    }
    return out;
}

void Client::Impl::recycle(Message&& message) {
    outbox_.recycle(std::move(message), in_flight_limit_.load(std::memory_order_relaxed));
}

void Client::Impl::set_sending(bool enabled) {
    {
        std::lock_guard lock(mutex_);
        sending_ = enabled;
        if (enabled) held_for_reconnect_ = false;
    }
    wake_sender_.notify_all();
}

bool Client::Impl::ready_to_send() const {
    if (quit_ || !sending_ || !link_up_.load(std::memory_order_relaxed) || !has_queued() ||
        suspect_waits()) {
        return false;
    }
    return detail::has_room(pending(), in_flight_limit_.load(std::memory_order_relaxed),
                            window_full_) &&
           (!next_awaits_ack() ||
            detail::has_acknowledged_room(pending_acknowledged(), own_unacknowledged_,
                                          acknowledged_limit_.load(std::memory_order_relaxed)));
}

bool Client::Impl::next_awaits_ack() const {
    if (!retry_.empty()) return retry_.begin()->second.message.qos > 0;
    const Message* next = outbox_.peek_next();
    return next != nullptr && next->qos > 0;
}

void Client::Impl::sender_main() {
    // Named for `top -H` and profiles (at most 15 characters).
    ::pthread_setname_np(::pthread_self(), "mqtt-sender");
    std::vector<Taken> taken;
    std::vector<Outgoing> burst;
    std::unique_lock lock(mutex_);
    for (;;) {
        sender_idle_ = true;
        wake_sender_.wait(lock, [this] { return quit_ || ready_to_send(); });
        sender_idle_ = false;
        if (quit_) {
            return;
        }
        // The lock is held to move publications between queues, never to build Paho's
        // messages: Paho's send thread completes QoS 0 publications under its own mutex and
        // waits for ours, and every publish waits for Paho's (#17: 12 % of the gateway's time
        // was spent in those two locks when the burst was built under ours).
        take_burst(taken);
        lock.unlock();
        prepare_burst(taken);
        lock.lock();
        // Nagle only for a backlog that waits on the sending itself. One that waits for PUBACKs
        // (the broker's Receive Maximum reached) gains nothing from fuller segments, and against
        // a broker that leaves Nagle on too (Mosquitto's default) each side then holds its next
        // segment until the other's delayed ACK: 40 ms stalls, a QoS 1 p99 4.4 x bare Paho's.
        const bool backlog = admit_burst(taken, burst);
        // A large backlog (the first publication of every tag, a reconnect's republish, an
        // outage's buffer) leaves its freed messages in malloc's arenas: once it has drained,
        // give them back, so that resident memory follows the live data.
        const bool trim = retry_.empty() && outbox_.release_after_backlog(kTrimAfterBacklog);
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

void Client::Impl::take_burst(std::vector<Taken>& taken) {
    const std::size_t limit = in_flight_limit_;
    const std::size_t acknowledged_limit = acknowledged_limit_;
    while (pending() < limit && !suspect_waits()) {
        if (!detail::has_acknowledged_room(pending_acknowledged(), own_unacknowledged_,
                                           acknowledged_limit) &&
            next_awaits_ack()) {
            break;
        }
        Taken& next = taken.emplace_back();
        if (!retry_.empty()) {
            auto retry = std::move(retry_.extract(retry_.begin()).mapped());
            next.message = std::move(retry.message);
            next.probe = retry.suspect;
        } else if (!outbox_.take_next(next.message)) {
            taken.pop_back();
            break;
        }
        ++taking_;
        if (next.message.qos > 0) ++taking_acknowledged_;
        if (next.probe) break;
    }
}

void Client::Impl::prepare_burst(std::vector<Taken>& taken) {
    const std::size_t max_packet_size = max_packet_size_;
    for (auto& next : taken) {
        if (auto problem = detail::publication_problem(next.message, max_packet_size);
            !problem.empty()) {
            refused_.fetch_add(1, std::memory_order_relaxed);
            log_refused(next.message.topic, problem);
            continue;
        }
        // Paho copies topic and payload: the window keeps our Message only for a re-send.
        next.out = to_paho(next.message);
    }
}

bool Client::Impl::admit_burst(std::vector<Taken>& taken, std::vector<Outgoing>& burst) {
    for (auto& next : taken) {
        if (!next.out) {
            recycle(std::move(next.message));
            if (stopping_) completed_.notify_all();  // no longer pending: stop() may be done
            continue;
        }
        const bool acknowledged = next.message.qos > 0;
        const auto id = in_flight_.add(std::move(next.message), acknowledged);
        if (next.probe) probe_ = id;
        burst.push_back({id, std::move(next.out)});
    }
    taken.clear();
    taking_ = 0;
    taking_acknowledged_ = 0;
    window_full_ = in_flight_.pending() >= in_flight_limit_;
    return window_full_ && has_queued();
}

void Client::Impl::send(std::uint64_t id, const paho::message_ptr& message) {
    try {
        client_->publish(message, to_context(id), publish_listener_);
    } catch (const paho::exception& e) {
        std::unique_lock lock(mutex_);
        auto item = in_flight_.complete(id);
        if (!item) {
            return;  // abandoned meanwhile by on_connection_lost
        }
        if (e.get_return_code() == MQTTASYNC_DISCONNECTED) {
            // Never left: no duplicate possible, and it proved nothing. A suspect stays one, to
            // be sent alone on the next connection; demoted, it would go out with others and
            // cost one more connection.
            const bool suspect = probe_ == id;
            if (suspect) probe_.reset();
            retry_.emplace(id, Retry{std::move(*item), suspect});
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
        if (probe_ == id) probe_.reset();
        publish_failures_.fetch_add(1, std::memory_order_relaxed);
        lock.unlock();
        completed_.notify_all();
        log_publish_failure(message->get_topic(), e.what());
    }
}

void Client::Impl::on_publish_done(std::uint64_t id, int rc, int reason_code,
                                   const std::string& reason) {
    std::string failed_topic;
    std::string dropped_topic;
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        auto item = in_flight_.complete(id);
        if (!item) {
            return;  // already re-queued or counted by on_connection_lost
        }
        if (rc == 0) {
            if (probe_ == id) probe_.reset();
            published_.fetch_add(1, std::memory_order_relaxed);
            if (item->ack_token != 0) {
                post([token = item->ack_token](Impl& self) {
                    if (self.on_acknowledged_) self.on_acknowledged_(token);
                });
            }
            recycle(std::move(*item));
        } else if (requeue_in_flight_ && item->qos > 0 && !stopping_ &&
                   !broker_refused(rc, reason_code)) {
            // No verdict of the broker's: failed because the connection went (Paho may report
            // that before its connection-lost handler runs). Sent again after the reconnect,
            // alone (requeue_after_loss); a broker's refusal is final.
            dropped_topic = requeue_after_loss(id, std::move(*item));
        } else {
            if (probe_ == id) probe_.reset();
            publish_failures_.fetch_add(1, std::memory_order_relaxed);
            failed_topic = std::move(item->topic);
        }
        wake = sender_idle_ && ready_to_send();
    }
    if (stopping_) {
        completed_.notify_all();
    }
    if (wake) {
        wake_sender_.notify_one();
    }
    if (!failed_topic.empty()) {
        log_publish_failure(failed_topic, reason);
    }
    if (!dropped_topic.empty()) {
        log_dropped_suspect(dropped_topic);
    }
}

std::uint64_t Client::Impl::reserve_own_slot() {
    std::lock_guard lock(mutex_);
    ++own_unacknowledged_;
    return own_generation_;
}

paho::delivery_token_ptr Client::Impl::publish_own(paho::message_ptr message,
                                                   std::uint64_t generation) {
    if (message->get_qos() == 0) return client_->publish(std::move(message));
    try {
        return client_->publish(std::move(message), to_context(generation),
                                own_publication_listener_);
    } catch (const paho::exception&) {
        release_own_slot(generation);
        throw;
    }
}

void Client::Impl::release_own_slot(std::uint64_t generation) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        // One of an earlier connection: on_connect has started this one's count afresh.
        if (generation != own_generation_ || own_unacknowledged_ == 0) return;
        --own_unacknowledged_;
        wake = sender_idle_ && ready_to_send();
    }
    if (stopping_) completed_.notify_all();
    if (wake) wake_sender_.notify_one();
}

std::string Client::Impl::requeue_after_loss(std::uint64_t id, Message&& message) {
    hold_for_reconnect();
    if (probe_ == id) {
        // It went alone, on a connection made after it became a suspect, and the connection
        // went again: the broker refuses it. One retry is all it gets.
        probe_.reset();
        refused_.fetch_add(1, std::memory_order_relaxed);
        return std::move(message.topic);
    }
    retry_.emplace(id, Retry{std::move(message), true});
    return {};
}

void Client::Impl::hold_for_reconnect() {
    if (held_for_reconnect_) return;  // once per loss, not once per abandoned publication
    held_for_reconnect_ = true;
    post([](Impl& self) {
        self.loss_hold_timer_.expires_after(kLossHold);
        self.loss_hold_timer_.async_wait(
            [w = self.weak_from_this()](const boost::system::error_code& ec) {
                auto held = w.lock();
                if (ec || !held) return;
                {
                    std::lock_guard lock(held->mutex_);
                    held->held_for_reconnect_ = false;
                }
                held->wake_sender_.notify_all();
            });
    });
}

void Client::Impl::log_dropped_suspect(const std::string& topic) {
    spdlog::error(
        "{} publication to {} failed again when it was sent alone (the broker closed the "
        "connection on it, or Paho refused it): it is dropped, so that it cannot block every "
        "connection after",
        options_.log_name, core::printable(topic));
}

void Client::Impl::log_refused(const std::string& topic, const std::string& problem) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = refused_log_.record(Clock::now());
    }
    if (count > 0) {
        spdlog::error(
            "{} publication to {} dropped: a broker would refuse it ({}) and close the "
            "connection ({} dropped since last report)",
            options_.log_name, core::printable(topic), problem, count);
    }
}

void Client::Impl::log_publish_failure(const std::string& topic, const std::string& reason) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = publish_failure_log_.record(Clock::now());
    }
    if (count > 0) {
        spdlog::warn("{} publish to {} failed: {} ({} failures since last report)",
                     options_.log_name, topic, reason, count);
    }
}

void Client::Impl::stop(std::chrono::milliseconds flush_timeout) {
    if (stopping_.exchange(true)) {
        return;
    }
    // The loop may no longer run: cancel its timer there if it does, and touch nothing of it
    // here. The sender thread keeps sending until the queue is flushed or the time is up.
    post([](Impl& self) {
        self.state_ = State::stopped;
        self.connected_ = false;
        self.reconnect_timer_.cancel();
        self.loss_hold_timer_.cancel();
    });
    const auto end_sender = [this] {
        {
            std::lock_guard lock(mutex_);
            quit_ = true;
        }
        wake_sender_.notify_all();
        if (sender_.joinable()) {
            sender_.join();
        }
    };
    const auto deadline = Clock::now() + flush_timeout;
    if (!link_up_ || !client_->is_connected()) {
        std::size_t lost = 0;
        {
            std::lock_guard lock(mutex_);
            lost = outbox_.size() + retry_.size();
        }
        end_sender();
        if (lost > 0) {
            spdlog::warn("{} stopping while disconnected: {} queued publications dropped",
                         options_.log_name, lost);
        }
        connected_ = false;
        return;
    }

    paho::delivery_token_ptr offline;
    if (!options_.availability_topic.empty()) {
        std::uint64_t generation = 0;
        if (options_.availability_qos > 0) {
            // Its slot first, so that the sender takes no freed one; then wait until the
            // window has room for it, or Paho would hold it until its next one-second cycle.
            generation = reserve_own_slot();
            std::unique_lock lock(mutex_);
            completed_.wait_until(lock, deadline, [this] {
                return pending_acknowledged() + own_unacknowledged_ <= acknowledged_limit_;
            });
        }
        try {
            offline = publish_own(paho::make_message(options_.availability_topic, "offline",
                                                     options_.availability_qos, true),
                                  generation);
        } catch (const paho::exception& e) {
            spdlog::warn("{} cannot publish availability: {}", options_.log_name, e.what());
        }
    }

    std::size_t unsent = 0;
    std::optional<Message> farewell;
    {
        std::unique_lock lock(mutex_);
        completed_.wait_until(lock, deadline, [this] { return !has_queued() && pending() == 0; });
        unsent = outbox_.size() + retry_.size() + pending();
        farewell = std::move(last_will_);
    }
    end_sender();
    // The will, said by ourselves after everything else (Sparkplug's NDEATH must be last).
    if (farewell) {
        try {
            offline = client_->publish(paho::make_message(farewell->topic, farewell->payload,
                                                          farewell->qos, farewell->retain));
        } catch (const paho::exception& e) {
            spdlog::warn("{} cannot publish the will on {}: {}", options_.log_name, farewell->topic,
                         e.what());
        }
    }
    if (offline) {
        const auto left = std::max(Clock::duration::zero(), deadline - Clock::now());
        try {
            offline->wait_for(std::chrono::duration_cast<std::chrono::milliseconds>(left));
        } catch (const paho::exception&) {
        }
    }
    if (unsent > 0) {
        spdlog::warn("{} stop: {} publications not confirmed within {} ms", options_.log_name,
                     unsent, flush_timeout.count());
    }
    try {
        client_->disconnect(paho::disconnect_options(std::chrono::seconds(1)))
            ->wait_for(std::chrono::seconds(2));
    } catch (const paho::exception& e) {
        spdlog::warn("{} disconnect failed: {}", options_.log_name, e.what());
    }
    link_up_ = false;
    connected_ = false;
    spdlog::info("{} disconnected from {}", options_.log_name, options_.url);
}

}  // namespace eip2mqtt::adapters::mqtt
