// The connection side of Client::Impl: connect, the CONNACK, losses, reconnect backoff and
// subscriptions, all on the loop.

#include <spdlog/spdlog.h>

#include "adapters/mqtt/detail/client_impl.hpp"

namespace eip2mqtt::adapters::mqtt {

using detail::kConnectTimeout;

Client::Impl::Impl(boost::asio::any_io_executor loop, ClientOptions options)
    : loop_(std::move(loop)),
      options_(std::move(options)),
      endpoint_(detail::parse_broker_url(options_.url)),
      // With a clean session Paho discards unacknowledged publications on reconnect, so we
      // resend them; with a kept session Paho resends them itself and we must not duplicate.
      requeue_in_flight_(!options_.session_bound &&
                         (options_.clean_start ||
                          (options_.version == 5 && options_.session_expiry.count() == 0))),
      reconnect_timer_(loop_),
      loss_hold_timer_(loop_),
      backoff_(options_.min_backoff, options_.max_backoff),
      outbox_(options_.buffer_max_messages, options_.batch_lane_max_messages, options_.batch_first),
      in_flight_limit_(std::max<std::size_t>(1, options_.max_in_flight)),
      acknowledged_limit_(in_flight_limit_.load()) {
    const bool v5 = options_.version == 5;
    paho::create_options create(v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    // Paho C refuses commands beyond maxBufferedMessages (default 100) even while connected:
    // room for max_in_flight publications, availability, subscribes and the disconnect.
    create.set_max_buffered_messages(
        static_cast<int>(std::min<std::size_t>(options_.max_in_flight + 64, 1 << 30)));
    client_ =
        std::make_unique<paho::async_client>(options_.url, options_.client_id, create, nullptr);

    detail::configure_connect_options(connect_options_, options_, endpoint_, kConnectTimeout);
    if (options_.tls && endpoint_ && !endpoint_->tls) {
        spdlog::warn("{} url {} is not ssl:// or wss://: mqtt.tls is ignored", options_.log_name,
                     options_.url);
    }

    // Paho's threads: copy, count, post; nothing else.
    client_->set_connection_lost_handler([this](const std::string& cause) {
        link_up_ = false;
        post([cause](Impl& self) { self.on_connection_lost(cause, cause.empty()); });
    });
    client_->set_disconnected_handler([this](const paho::properties&, paho::ReasonCode reason) {
        link_up_ = false;
        post([reason](Impl& self) {
            self.on_connection_lost(detail::describe_disconnect(
                static_cast<int>(reason), paho::exception::reason_code_str(reason),
                self.options_.client_id));
        });
    });
    client_->set_message_callback([this](paho::const_message_ptr msg) {
        Incoming in;
        in.topic = msg->get_topic();
        in.payload = msg->get_payload_str();
        in.retained = msg->is_retained();
        const paho::properties& props = msg->get_properties();
        if (props.contains(paho::property::RESPONSE_TOPIC)) {
            in.response_topic = paho::get<std::string>(props, paho::property::RESPONSE_TOPIC);
        }
        if (props.contains(paho::property::CORRELATION_DATA)) {
            in.correlation_data = paho::get<std::string>(props, paho::property::CORRELATION_DATA);
        }
        if (props.contains(paho::property::MESSAGE_EXPIRY_INTERVAL)) {
            in.message_expiry_s =
                paho::get<std::uint32_t>(props, paho::property::MESSAGE_EXPIRY_INTERVAL);
        }
        received_.fetch_add(1, std::memory_order_relaxed);
        post([in = std::move(in)](Impl& self) mutable {
            if (self.on_message_ && self.state_ != State::stopped) {
                self.on_message_(std::move(in));
            }
        });
    });
    sender_ = std::thread([this] { sender_main(); });
}

Client::Impl::~Impl() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
    }
    wake_sender_.notify_all();
    if (sender_.joinable()) {
        sender_.join();
    }
    try {
        client_->disable_callbacks();
    } catch (const paho::exception&) {
    }
    // Without a clean stop() the broker publishes our will: that is what "offline" means.
    client_.reset();
}

void Client::Impl::do_connect() {
    if (state_ == State::stopped) {
        return;
    }
    state_ = State::connecting;
    try {
        if (options_.will) {
            Message will = options_.will();
            connect_options_.set_will(
                paho::will_options(will.topic, will.payload, will.qos, will.retain));
            std::lock_guard lock(mutex_);
            last_will_ = std::move(will);
        }
        connect_token_ = client_->connect(connect_options_, nullptr, connect_listener_);
    } catch (const paho::exception& e) {
        on_connect(false, e.what());
    }
}

void Client::Impl::on_connect(bool ok, std::string reason, int return_code) {
    if (state_ != State::connecting) {
        return;  // stopped meanwhile
    }
    if (ok && !client_->is_connected()) {
        ok = false;  // lost again before this ran
        reason = "connection lost right after connect";
    }
    if (!ok) {
        on_connect_failed(std::move(reason), return_code);
        return;
    }

    state_ = State::connected;
    connected_at_ = Clock::now();
    link_up_ = true;
    connected_ = true;
    connects_.fetch_add(1, std::memory_order_relaxed);
    backoff_.reset();
    update_in_flight_limit();
    connect_failure_log_.reset();
    spdlog::info("{} connected to {}", options_.log_name, options_.url);

    if (endpoint_) {
        nagle_.attach(detail::sockets_connected_to(endpoint_->host, endpoint_->port));
    }
    // Subscribe before announcing `online`: the broker handles one connection's packets in
    // order, so whoever sees `online` can already write to us.
    renew_subscriptions(subscriptions_);
    {
        // Own publications of an earlier connection are answered there or never.
        std::lock_guard lock(mutex_);
        own_unacknowledged_ = 0;
        ++own_generation_;
    }
    try {
        if (!options_.availability_topic.empty()) {
            publish_own(paho::make_message(options_.availability_topic, "online",
                                           options_.availability_qos, true),
                        options_.availability_qos > 0 ? reserve_own_slot() : 0);
        }
    } catch (const paho::exception& e) {
        spdlog::warn("{} cannot publish availability: {}", options_.log_name, e.what());
    }
    if (on_connected_) {
        on_connected_();
    }
    set_sending(true);
}

void Client::Impl::on_connect_failed(std::string reason, int return_code) {
    reason = explain_connect_failure(std::move(reason));
    if (options_.version == 5) {
        if (auto refusal =
                detail::mqtt5_refusal(return_code, reason, endpoint_ && endpoint_->tls)) {
            // Paho has no words for the 3.1.1 return code 1 ("Unknown error code 1").
            reason = return_code == 1 ? std::move(*refusal) : reason + ": " + *refusal;
        }
    }
    if (const auto count = connect_failure_log_.record(Clock::now())) {
        if (count == 1) {
            spdlog::warn("{} cannot connect to {}: {}", options_.log_name, options_.url, reason);
        } else {
            spdlog::warn("{} cannot connect to {}: {} ({} failed attempts)", options_.log_name,
                         options_.url, reason, count);
        }
        spdlog::info("{} reconnecting in {} ms", options_.log_name, schedule_reconnect().count());
    } else {
        schedule_reconnect();
    }
}

std::string Client::Impl::explain_connect_failure(std::string reason) const {
    if (reason != paho::exception::error_str(MQTTASYNC_FAILURE)) {
        return reason;  // the broker gave a reason code, or Paho a specific error
    }
    try {
        // Completed (or about to be, see update_in_flight_limit): throws its error, which
        // carries Paho's message.
        if (connect_token_) {
            connect_token_->wait_for(std::chrono::seconds(1));
        }
    } catch (const paho::exception& e) {
        if (!e.get_message().empty() && e.get_message() != reason) {
            reason += ": " + e.get_message();
        }
    }
    if (endpoint_ && endpoint_->tls) {
        // Paho C++ 1.2 cannot safely report OpenSSL's reason (see the constructor).
        reason +=
            " (TLS handshake failed or the broker closed the connection: check that "
            "mqtt.tls.ca_file signed the broker's certificate, that the certificate names " +
            endpoint_->host + ", and whether the broker requires a client certificate)";
    }
    return reason;
}

void Client::Impl::update_in_flight_limit() {
    // MQTT 5 §3.2.2.3.3: the broker's Receive Maximum, 65535 when absent (Mosquitto sends 20).
    // Paho C sends no more QoS >= 1 publications than that and queues the rest until its next
    // one-second cycle rather than on PUBACK, which capped us at 20 messages/s: the sender must
    // not hand it more of them, with our own `online` and `offline` counted while unacknowledged
    // (detail/send_room.hpp; QoS 0 are not counted). (The token the listener sees lacks the
    // CONNACK properties in Paho C++ 1.2; the one connect() returned has them.)
    std::size_t receive_maximum = 65535;
    try {
        // The listener posted on_connect just before Paho marks the token complete and
        // stores the response: wait for that (microseconds; bounded).
        if (connect_token_ && connect_token_->wait_for(std::chrono::seconds(1))) {
            const paho::connect_response response = connect_token_->get_connect_response();
            const paho::properties& props = response.get_properties();
            if (props.contains(paho::property::RECEIVE_MAXIMUM)) {
                receive_maximum = paho::get<std::uint16_t>(props, paho::property::RECEIVE_MAXIMUM);
            }
            max_packet_size_ =
                props.contains(paho::property::MAXIMUM_PACKET_SIZE)
                    ? paho::get<std::uint32_t>(props, paho::property::MAXIMUM_PACKET_SIZE)
                    : detail::max_mqtt_packet_size;
        }
    } catch (const std::exception&) {
        // No CONNACK properties (MQTT 3.1.1): no limit beyond ours.
    }
    acknowledged_limit_ =
        std::max<std::size_t>(1, std::min(options_.max_in_flight, receive_maximum));
}

void Client::Impl::on_connection_lost(std::string cause, bool silent) {
    if (state_ != State::connected) {
        return;
    }
    if (silent_losses_.on_loss(silent, Clock::now() - connected_at_)) {
        cause = "no reason given: " + detail::SilentLossPattern::explain(options_.client_id);
    } else if (silent) {
        cause = "no reason given (no DISCONNECT from the broker)";
    }
    connected_ = false;
    connection_losses_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("{} connection to {} lost: {}", options_.log_name, options_.url, cause);
    nagle_.detach();
    std::string dropped;
    {
        // Whatever Paho did not confirm is either sent again (QoS >= 1, clean session) or
        // counted as failed. Completions arriving later find nothing and are ignored, so
        // nothing is counted twice.
        std::lock_guard lock(mutex_);
        sending_ = false;
        if (options_.session_bound) {
            const auto stale = outbox_.discard_all() + retry_.size();
            retry_.clear();
            discarded_.fetch_add(stale, std::memory_order_relaxed);
        }
        if (requeue_in_flight_) {
            in_flight_.abandon_all([&](std::uint64_t id, Message&& message) {
                if (message.qos > 0) {
                    if (auto topic = requeue_after_loss(id, std::move(message)); !topic.empty()) {
                        dropped = std::move(topic);
                    }
                } else {
                    publish_failures_.fetch_add(1, std::memory_order_relaxed);
                }
            });
        }
    }
    completed_.notify_all();
    if (!dropped.empty()) {
        log_dropped_suspect(dropped);
    }
    spdlog::info("{} reconnecting in {} ms", options_.log_name, schedule_reconnect().count());
}

std::chrono::milliseconds Client::Impl::schedule_reconnect() {
    state_ = State::waiting;
    // Doubling, but never more than a quarter of the outage's age: a short outage is noticed
    // soon after the broker is back (detail/reconnect_backoff.hpp).
    const auto delay = backoff_.next(Clock::now());
    reconnect_timer_.expires_after(delay);
    reconnect_timer_.async_wait([w = weak_from_this()](boost::system::error_code ec) {
        auto self = w.lock();
        if (ec == boost::asio::error::operation_aborted || !self) {
            return;
        }
        if (self->state_ == State::waiting) {
            self->do_connect();
        }
    });
    return delay;
}

void Client::Impl::renew_subscriptions(const std::vector<std::string>& filters) {
    if (filters.empty() || state_ != State::connected) {
        return;
    }
    const bool v5 = options_.version == 5;
    // no_local: never hear our own publications. retain-as-published: a write published
    // with retain keeps its flag when forwarded live, as it has when a new subscription
    // fetches it later, so the gateway can refuse retained writes either way.
    const paho::subscribe_options opt(v5, v5);
    try {
        // One SUBSCRIBE per filter: Paho C++ 1.2's many-topic overload crashes inside
        // MQTTAsync_subscribeMany when given subscribe options, and its one-topic overload is
        // the only one that passes them on.
        for (const auto& filter : filters) {
            client_->subscribe(filter, 1, nullptr, subscribe_listener_, opt);
        }
    } catch (const paho::exception& e) {
        spdlog::warn("{} subscribe failed on {}: {}", options_.log_name, options_.url, e.what());
    }
}

}  // namespace eip2mqtt::adapters::mqtt
