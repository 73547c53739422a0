// The public Client: a thin façade over its parts (detail/client_impl.hpp), the Connection on
// the loop and the Sender with its thread.

#include "eip2mqtt/adapters/mqtt/client.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "adapters/mqtt/detail/client_impl.hpp"
#include "adapters/mqtt/detail/paho_connect.hpp"
#include "adapters/mqtt/detail/paho_trace.hpp"

namespace eip2mqtt::adapters::mqtt {

namespace {

std::unique_ptr<::mqtt::async_client> make_paho_client(const ClientOptions& options) {
    if (options.urls.empty()) {
        throw std::invalid_argument(options.log_name + " client without a broker URL");
    }
    detail::quiet_paho_trace(std::getenv("MQTT_C_CLIENT_TRACE"));
    // Paho's connects end in its send thread, CONNECT and CONNACK at once, TLS's aside
    // (paho_connect.hpp).
    static_cast<void>(detail::paho_connects_at_once(options.urls));
    ::mqtt::create_options create(options.version == 5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    // Paho C refuses commands beyond maxBufferedMessages (default 100) even while connected:
    // room for max_in_flight publications, availability, subscribes and the disconnect.
    create.set_max_buffered_messages(
        static_cast<int>(std::min<std::size_t>(options.max_in_flight + 64, 1 << 30)));
    // The first broker; each connect names its own (Connection::do_connect).
    return std::make_unique<::mqtt::async_client>(options.urls.front(), options.client_id, create,
                                                  nullptr);
}

}  // namespace

Client::Impl::Impl(boost::asio::any_io_executor loop, ClientOptions options)
    : options_(std::move(options)),
      loop_(std::move(loop)),
      paho_(make_paho_client(options_)),
      sender_(options_, *paho_, loop_, nagle_),
      connection_(options_, *paho_, loop_, sender_, nagle_) {}

Client::Impl::~Impl() {
    sender_.end_thread();
    try {
        paho_->disable_callbacks();
    } catch (const ::mqtt::exception&) {
    }
    // Without a clean stop() the broker publishes our will: that is what "offline" means.
    paho_.reset();
}

void Client::Impl::start_parts() {
    loop_.bind(weak_from_this());
    sender_.start_thread();
}

Client::Client(boost::asio::any_io_executor loop, ClientOptions options)
    : impl_(std::make_shared<Impl>(std::move(loop), std::move(options))) {
    impl_->start_parts();
}

Client::~Client() = default;

void Client::set_on_connected(ConnectedHandler handler) {
    impl_->connection().set_on_connected(std::move(handler));
}

void Client::set_on_message(MessageHandler handler) {
    impl_->connection().set_on_message(std::move(handler));
}

void Client::set_on_acknowledged(AcknowledgedHandler handler) {
    impl_->sender().set_on_acknowledged(std::move(handler));
}

void Client::set_subscriptions(std::vector<std::string> filters) {
    impl_->connection().set_subscriptions(std::move(filters));
}

void Client::start() { impl_->connection().start(); }

void Client::end_session() { impl_->connection().end_session(); }

void Client::leave_broker() { impl_->connection().leave_broker(); }

void Client::publish(Message&& message) {
    if (!impl_->connection().accepts_publications()) {
        impl_->sender().count_discarded();
        message.clear();
        return;
    }
    impl_->sender().enqueue(message);
}

void Client::stop(std::chrono::milliseconds flush_timeout) { impl_->stop(flush_timeout); }

bool Client::connected() const { return impl_->connection().connected(); }

std::size_t Client::max_packet_size() const { return impl_->sender().max_packet_size(); }

ClientStats Client::stats() const {
    ClientStats stats;
    impl_->connection().add_stats(stats);
    impl_->sender().add_stats(stats);
    return stats;
}

void Client::set_buffer_capacity(std::size_t max_messages) {
    impl_->sender().set_buffer_capacity(max_messages);
}

void Client::set_batch_first(bool batch_first) { impl_->sender().set_batch_first(batch_first); }

}  // namespace eip2mqtt::adapters::mqtt
