// The Sender's front: queueing from any thread, the connection's events, stop()'s steps.

#include "adapters/mqtt/detail/sender.hpp"

#include <algorithm>

#include "adapters/mqtt/detail/publication_check.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace {

bool requeues_in_flight(const ClientOptions& options) {
    return !options.session_bound &&
           (options.clean_start || (options.version == 5 && options.session_expiry.count() == 0));
}

}  // namespace

Sender::Sender(const ClientOptions& options, ::mqtt::async_client& paho, const LoopPost& loop,
               NagleSwitch& nagle)
    : options_(options),
      paho_(paho),
      loop_(loop),
      nagle_(nagle),
      requeue_in_flight_(requeues_in_flight(options)),
      hold_timer_(loop.executor()),
      ledger_(options.buffer_max_messages, options.batch_lane_max_messages, options.batch_first,
              options.max_in_flight),
      max_packet_size_(max_mqtt_packet_size) {}

Sender::~Sender() { end_thread(); }

void Sender::start_thread() {
    thread_ = std::thread([this] { sender_main(); });
}

void Sender::enqueue(Message& message) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        ledger_.push(message);
        wake = sender_idle_ && ready_to_send();
    }
    if (wake) {
        wake_sender_.notify_one();
    }
}

void Sender::set_buffer_capacity(std::size_t max_messages) {
    std::lock_guard lock(mutex_);
    ledger_.outbox().set_capacity(max_messages);
}

void Sender::set_batch_first(bool batch_first) {
    std::lock_guard lock(mutex_);
    ledger_.outbox().set_batch_first(batch_first);
}

void Sender::add_stats(ClientStats& stats) const {
    stats.published = published_;
    stats.publish_failures = publish_failures_;
    stats.refused = refused_;
    stats.discarded = discarded_;
    std::lock_guard lock(mutex_);
    const Outbox& outbox = ledger_.outbox();
    stats.queued = ledger_.queued();
    stats.in_flight = ledger_.pending();
    stats.dropped_overflow = outbox.tags().dropped_overflow() + outbox.batch().dropped_overflow();
    stats.coalesced = outbox.tags().coalesced();
}

void Sender::on_connected(std::size_t receive_maximum, std::optional<std::size_t> max_packet_size) {
    if (max_packet_size) max_packet_size_ = *max_packet_size;
    std::lock_guard lock(mutex_);
    ledger_.set_acknowledged_limit(receive_maximum);
    ledger_.new_connection();
}

void Sender::set_sending(bool enabled) {
    {
        std::lock_guard lock(mutex_);
        sending_ = enabled;
        if (enabled) ledger_.release_hold();
    }
    wake_sender_.notify_all();
}

void Sender::wait_for_own_slots(Clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    completed_.wait_until(lock, deadline, [this] { return ledger_.own_slots_fit(); });
}

std::size_t Sender::flush(Clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    completed_.wait_until(lock, deadline,
                          [this] { return !ledger_.has_queued() && ledger_.pending() == 0; });
    return ledger_.queued() + ledger_.pending();
}

std::size_t Sender::queued() const {
    std::lock_guard lock(mutex_);
    return ledger_.queued();
}

void Sender::end_thread() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
    }
    wake_sender_.notify_all();
    if (thread_.joinable()) {
        thread_.join();
    }
}

}  // namespace eip2mqtt::adapters::mqtt::detail
