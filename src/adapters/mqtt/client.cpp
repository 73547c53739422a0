// The public Client: a facade over Client::Impl (detail/client_impl.hpp), which the loop, the
// sender thread and Paho's threads share.

#include "eip2mqtt/adapters/mqtt/client.hpp"

#include "adapters/mqtt/detail/client_impl.hpp"

namespace eip2mqtt::adapters::mqtt {

Client::Client(boost::asio::any_io_executor loop, ClientOptions options)
    : impl_(std::make_shared<Impl>(std::move(loop), std::move(options))) {}

Client::~Client() = default;

void Client::set_on_connected(ConnectedHandler handler) {
    impl_->on_connected_ = std::move(handler);
}

void Client::set_on_message(MessageHandler handler) { impl_->on_message_ = std::move(handler); }

void Client::set_on_acknowledged(AcknowledgedHandler handler) {
    impl_->on_acknowledged_ = std::move(handler);
}

void Client::set_subscriptions(std::vector<std::string> filters) {
    Impl& impl = *impl_;
    std::set<std::string> old(impl.subscriptions_.begin(), impl.subscriptions_.end());
    std::set<std::string> now(filters.begin(), filters.end());
    std::vector<std::string> added;
    std::vector<std::string> removed;
    std::set_difference(now.begin(), now.end(), old.begin(), old.end(), std::back_inserter(added));
    std::set_difference(old.begin(), old.end(), now.begin(), now.end(),
                        std::back_inserter(removed));
    impl.subscriptions_ = std::move(filters);
    if (impl.state_ != Impl::State::connected) {
        return;  // subscribed on the next connect
    }
    impl.renew_subscriptions(added);
    if (!removed.empty()) {
        try {
            impl.client_->unsubscribe(paho::string_collection::create(removed));
        } catch (const paho::exception& e) {
            spdlog::warn("{} unsubscribe failed on {}: {}", impl.options_.log_name,
                         impl.options_.url, e.what());
        }
    }
}

void Client::start() {
    if (impl_->state_ == Impl::State::idle) {
        impl_->do_connect();
    }
}

void Client::publish(Message&& message) {
    if (impl_->options_.session_bound && impl_->state_ != Impl::State::connected) {
        impl_->discarded_.fetch_add(1, std::memory_order_relaxed);
        message.clear();
        return;
    }
    impl_->enqueue(message);
}

void Client::stop(std::chrono::milliseconds flush_timeout) { impl_->stop(flush_timeout); }

bool Client::connected() const { return impl_->connected_; }

std::size_t Client::max_packet_size() const { return impl_->max_packet_size_; }

ClientStats Client::stats() const {
    const Impl& impl = *impl_;
    ClientStats s;
    s.connected = impl.connected_;
    s.published = impl.published_;
    s.publish_failures = impl.publish_failures_;
    s.connects = impl.connects_;
    s.connection_losses = impl.connection_losses_;
    s.received = impl.received_;
    s.refused = impl.refused_;
    s.discarded = impl.discarded_;
    std::lock_guard lock(impl.mutex_);
    s.queued = impl.outbox_.size() + impl.retry_.size();
    s.in_flight = impl.pending();
    s.dropped_overflow =
        impl.outbox_.tags().dropped_overflow() + impl.outbox_.batch().dropped_overflow();
    s.coalesced = impl.outbox_.tags().coalesced();
    return s;
}

void Client::set_buffer_capacity(std::size_t max_messages) {
    std::lock_guard lock(impl_->mutex_);
    impl_->outbox_.set_capacity(max_messages);
}

void Client::set_batch_first(bool batch_first) {
    std::lock_guard lock(impl_->mutex_);
    impl_->outbox_.set_batch_first(batch_first);
}

}  // namespace eip2mqtt::adapters::mqtt
