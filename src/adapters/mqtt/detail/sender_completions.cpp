// What Paho tells the Sender: completions, failures, a lost connection, and the client's own
// publications' slots.

#include <spdlog/spdlog.h>

#include "adapters/mqtt/detail/sender.hpp"
#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace {

/// How long the thread holds after a loss-like failure if the connection does not go meanwhile.
constexpr auto kLossHold = std::chrono::seconds(1);

}  // namespace

void Sender::PublishListener::on_success(const ::mqtt::token& tok) {
    sender_.on_publish_done(from_context(tok.get_user_context()), 0, 0, {});
}

void Sender::PublishListener::on_failure(const ::mqtt::token& tok) {
    sender_.on_publish_done(from_context(tok.get_user_context()),
                            tok.get_return_code() == 0 ? -1 : tok.get_return_code(),
                            tok.get_reason_code(), describe_failure(tok));
}

void Sender::OwnPublicationListener::on_success(const ::mqtt::token& tok) {
    sender_.release_own_slot(from_context(tok.get_user_context()));
}

void Sender::OwnPublicationListener::on_failure(const ::mqtt::token& tok) {
    sender_.release_own_slot(from_context(tok.get_user_context()));
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
            published_.fetch_add(1, std::memory_order_relaxed);
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

bool Sender::broker_refused(int rc, int reason_code) const {
    return options_.version == 5 && rc != MQTTASYNC_DISCONNECTED &&
           rc != MQTTASYNC_OPERATION_INCOMPLETE && link_up_ && reason_code >= 0x80 &&
           reason_code <= 0xA2;
}

void Sender::on_connection_lost() {
    std::string dropped;
    {
        // Whatever Paho did not confirm is either sent again (QoS >= 1, clean session) or
        // counted as failed. Completions arriving later find nothing and are ignored, so
        // nothing is counted twice.
        std::lock_guard lock(mutex_);
        sending_ = false;
        if (options_.session_bound) {
            discarded_.fetch_add(ledger_.discard_queued(), std::memory_order_relaxed);
        }
        if (requeue_in_flight_) {
            ledger_.abandon_in_flight([&](std::uint64_t id, Message&& message) {
                if (message.qos == 0) {
                    publish_failures_.fetch_add(1, std::memory_order_relaxed);
                } else if (auto topic = requeue_after_loss(id, std::move(message));
                           !topic.empty()) {
                    dropped = std::move(topic);
                }
            });
        }
    }
    completed_.notify_all();
    if (!dropped.empty()) {
        log_dropped_suspect(dropped);
    }
}

void Sender::wait_idle() {
    std::unique_lock lock(mutex_);
    idle_wanted_ = true;
    completed_.wait(lock, [this] { return sender_idle_ || quit_; });
    idle_wanted_ = false;
}

std::string Sender::requeue_after_loss(std::uint64_t id, Message&& message) {
    hold_for_reconnect();
    auto dropped = ledger_.requeue_suspect(id, std::move(message));
    if (!dropped.empty()) {
        refused_.fetch_add(1, std::memory_order_relaxed);
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
            wake_sender_.notify_all();
        }));
    });
}

std::uint64_t Sender::reserve_own_slot() {
    std::lock_guard lock(mutex_);
    return ledger_.reserve_own_slot();
}

::mqtt::delivery_token_ptr Sender::publish_own(::mqtt::message_ptr message,
                                               std::uint64_t generation) {
    if (message->get_qos() == 0) return paho_.publish(std::move(message));
    try {
        return paho_.publish(std::move(message), to_context(generation), own_publication_listener_);
    } catch (const ::mqtt::exception&) {
        release_own_slot(generation);
        throw;
    }
}

void Sender::release_own_slot(std::uint64_t generation) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        if (!ledger_.release_own_slot(generation)) return;
        wake = sender_idle_ && ready_to_send();
    }
    if (stopping_) completed_.notify_all();
    if (wake) wake_sender_.notify_one();
}

void Sender::log_dropped_suspect(const std::string& topic) {
    spdlog::error(
        "{} publication to {} failed again when it was sent alone (the broker closed the "
        "connection on it, or Paho refused it): it is dropped, so that it cannot block every "
        "connection after",
        options_.log_name, core::printable(topic));
}

void Sender::log_refused(const std::string& topic, const std::string& problem) {
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

void Sender::log_publish_failure(const std::string& topic, const std::string& reason) {
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

}  // namespace eip2mqtt::adapters::mqtt::detail
