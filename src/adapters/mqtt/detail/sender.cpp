// The Sender's front: queueing from any thread, the connection's events, the client's own
// publications, stop()'s steps.

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
      log_(options.log_name, *options.clock),
      max_packet_size_(max_mqtt_packet_size),
      properties_(options) {}

Sender::~Sender() { end_thread(); }

void Sender::start_thread() {
    thread_ = std::thread([this] { sender_main(); });
}

void Sender::enqueue(Message& message) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        ledger_.push(message);
        wake = signals_.sleeping() && ready_to_send();
    }
    if (wake) {
        signals_.wake_one();
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
    counters_.add_to(stats);
    std::lock_guard lock(mutex_);
    const Outbox& outbox = ledger_.outbox();
    stats.queued = ledger_.queued();
    stats.in_flight = ledger_.pending();
    stats.dropped_overflow = outbox.tags().dropped_overflow() + outbox.batch().dropped_overflow();
    stats.coalesced = outbox.tags().coalesced();
}

// --- the connection's events ---------------------------------------------------------------

void Sender::on_connected(std::size_t receive_maximum, std::optional<std::size_t> max_packet_size,
                          std::uint16_t topic_alias_maximum) {
    if (max_packet_size) max_packet_size_ = *max_packet_size;
    // Before the thread may send on this connection (set_sending): no alias of the last one.
    properties_.on_connected(topic_alias_maximum);
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
    signals_.wake_all();
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
            SenderCounters::bump(counters_.discarded, ledger_.discard_queued());
        }
        if (requeue_in_flight_) {
            ledger_.abandon_in_flight([&](std::uint64_t id, Message&& message) {
                if (message.qos == 0) {
                    SenderCounters::bump(counters_.publish_failures);
                } else if (auto topic = requeue_after_loss(id, std::move(message));
                           !topic.empty()) {
                    dropped = std::move(topic);
                }
            });
        }
    }
    signals_.completed();
    if (!dropped.empty()) {
        log_.dropped_suspect(dropped);
    }
}

void Sender::wait_idle() {
    SenderSignals::Lock lock(mutex_);
    signals_.wait_idle(lock);
}

// --- the client's own publications ---------------------------------------------------------

void Sender::OwnPublicationListener::on_success(const ::mqtt::token& tok) {
    sender_.release_own_slot(from_context(tok.get_user_context()));
}

void Sender::OwnPublicationListener::on_failure(const ::mqtt::token& tok) {
    sender_.release_own_slot(from_context(tok.get_user_context()));
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
        wake = signals_.sleeping() && ready_to_send();
    }
    if (stopping_) signals_.completed();
    if (wake) signals_.wake_one();
}

// --- stop()'s steps ------------------------------------------------------------------------

void Sender::wait_for_own_slots(core::MonoTime deadline) {
    SenderSignals::Lock lock(mutex_);
    signals_.wait_completed_until(lock, deadline, [this] { return ledger_.own_slots_fit(); });
}

std::size_t Sender::flush(core::MonoTime deadline) {
    SenderSignals::Lock lock(mutex_);
    signals_.wait_completed_until(
        lock, deadline, [this] { return !ledger_.has_queued() && ledger_.pending() == 0; });
    return ledger_.queued() + ledger_.pending();
}

std::size_t Sender::queued() const {
    std::lock_guard lock(mutex_);
    return ledger_.queued();
}

void Sender::end_thread() {
    {
        std::lock_guard lock(mutex_);
        signals_.quit();
    }
    signals_.wake_all();
    if (thread_.joinable()) {
        thread_.join();
    }
}

}  // namespace eip2mqtt::adapters::mqtt::detail
