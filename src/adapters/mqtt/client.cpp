#include "eip2mqtt/adapters/mqtt/client.hpp"

#include <malloc.h>
#include <mqtt/async_client.h>
#include <pthread.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

#include "adapters/mqtt/detail/broker_url.hpp"
#include "adapters/mqtt/detail/connect_options.hpp"
#include "adapters/mqtt/detail/in_flight_window.hpp"
#include "adapters/mqtt/detail/publication_check.hpp"
#include "adapters/mqtt/detail/reconnect_backoff.hpp"
#include "adapters/mqtt/detail/tcp_nodelay.hpp"
#include "eip2mqtt/adapters/mqtt/publish_queue.hpp"
#include "eip2mqtt/core/printable.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace {

namespace paho = ::mqtt;
using Clock = std::chrono::steady_clock;

/// How long the sender holds after a dropped suspect if the connection does not go meanwhile.
constexpr auto kLossHold = std::chrono::seconds(1);
constexpr auto kConnectTimeout = std::chrono::seconds(10);
/// Queued publications past which the memory of a drained backlog is given back (malloc_trim
/// walks every arena: worth it after a burst, not after every message).
constexpr std::size_t kTrimAfterBacklog = 10000;

std::string describe_failure(const paho::token& tok) {
    const int rc = tok.get_return_code();
    const int reason = tok.get_reason_code();
    std::string text = paho::exception::error_str(rc);
    if (reason == 0 && rc >= 0x80) {
        // Paho C++ 1.2 reports a refused MQTT 5 CONNACK as a return code holding the reason
        // code (e.g. 135, Not authorized), which error_str does not know.
        return paho::exception::reason_code_str(rc);
    }
    if (reason != 0) {
        text += fmt::format(" ({})", paho::exception::reason_code_str(reason));
    }
    return text;
}

void* to_context(std::uint64_t id) {
    return reinterpret_cast<void*>(static_cast<std::uintptr_t>(id));
}
std::uint64_t from_context(void* ctx) { return reinterpret_cast<std::uintptr_t>(ctx); }

}  // namespace

/// Threading: the loop runs connect, reconnect and the user's handlers. The sender thread hands
/// queued publications to Paho. Paho's threads run the listeners below. Publication state (the
/// queues, what is in flight, the sender's wake-up conditions) is guarded by mutex_, held for
/// queue operations only, never across a Paho call; everything else the listeners learn is
/// posted to the loop.
struct Client::Impl : std::enable_shared_from_this<Impl> {
    Impl(boost::asio::any_io_executor loop, ClientOptions options);
    ~Impl();

    // --- loop ----------------------------------------------------------------------------
    void do_connect();
    void on_connect(bool ok, std::string reason);
    void on_connection_lost(std::string cause);
    /// Adds what connect_token_ knows and, over TLS, what to check, to a generic reason.
    std::string explain_connect_failure(std::string reason) const;
    void update_in_flight_limit();
    /// Arms the backoff timer; returns the delay.
    std::chrono::milliseconds schedule_reconnect();
    void renew_subscriptions(const std::vector<std::string>& filters);

    // --- any thread ----------------------------------------------------------------------
    /// Queues `message` in its lane and wakes the sender if it sleeps.
    void enqueue(Message& message);
    void recycle(Message&& message);
    /// Lets the sender hand publications to Paho (after a connect) or stops it (loss, stop).
    void set_sending(bool enabled);
    /// A Paho listener: publication `id` completed with Paho return code `rc` and, when the
    /// broker refused it (MQTT 5), its reason code (>= 0x80).
    void on_publish_done(std::uint64_t id, int rc, int reason_code, const std::string& reason);
    void log_publish_failure(const std::string& topic, const std::string& reason);
    void stop(std::chrono::milliseconds flush_timeout);

    // --- sender thread -------------------------------------------------------------------
    void sender_main();
    /// Paho's publish of one taken message; a synchronous refusal is handled here.
    void send(std::uint64_t id, const paho::message_ptr& message);

    // --- under mutex_ --------------------------------------------------------------------
    bool has_queued() const { return !retry_.empty() || !queue_.empty() || !batch_queue_.empty(); }
    /// Whether the sender has something to send and room to send it. After it filled the
    /// window it waits until an eighth of the window completed, so that it wakes once per
    /// burst rather than once per completion, yet keeps the window nearly full: at QoS 1 a
    /// busy broker's PUBACKs take milliseconds, and throughput is what is in flight over that
    /// time (refilling at a quarter cost a third of it).
    bool ready_to_send() const;
    /// Takes the next publication from the two lanes in turn (re-sent ones are taken by the
    /// sender itself, see sender_main).
    bool take_next(Message& message);
    /// A suspect goes alone: nothing else is sent while one is in flight, and one waits until
    /// nothing is in flight.
    bool suspect_waits() const {
        return probe_.has_value() || held_for_reconnect_ ||
               (!retry_.empty() && retry_.begin()->second.suspect && !in_flight_.empty());
    }
    /// A publication in flight when the connection went: sent again after the reconnect as a
    /// suspect, alone; the suspect in flight alone when it goes again is dropped, since the
    /// broker closes the connection on a publication it refuses. Returns the topic of a
    /// dropped one (empty otherwise).
    std::string requeue_after_loss(std::uint64_t id, Message&& message);
    /// Called when a publication fails the way a connection loss makes it fail: Paho reports
    /// that before its connection-lost handler runs, so the sender holds everything until the
    /// next connect, lest a suspect be sent "alone" on the dying connection and be blamed
    /// (dropped) for a loss it did not cause. Should the connection survive, the hold ends
    /// after kLossHold. Under mutex_.
    void hold_for_reconnect();
    void log_refused(const std::string& topic, const std::string& problem);
    void log_dropped_suspect(const std::string& topic);
    /// Whether a failed publication was refused by the broker itself: an MQTT 5 PUBACK with a
    /// failure reason code (0x80..0xA2) on a live connection. MQTT 3.1.1 has no such verdict,
    /// and Paho's own failures (a discarded or disconnected operation) carry other codes.
    bool broker_refused(int rc, int reason_code) const {
        return options_.version == 5 && rc != MQTTASYNC_DISCONNECTED &&
               rc != MQTTASYNC_OPERATION_INCOMPLETE && link_up_ && reason_code >= 0x80 &&
               reason_code <= 0xA2;
    }

    template <class F>
    void post(F&& f) {
        boost::asio::post(loop_, [w = weak_from_this(), f = std::forward<F>(f)]() mutable {
            if (auto self = w.lock()) {
                f(*self);
            }
        });
    }

    struct PublishListener final : paho::iaction_listener {
        explicit PublishListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token& tok) override {
            impl_.on_publish_done(from_context(tok.get_user_context()), 0, 0, {});
        }
        void on_failure(const paho::token& tok) override {
            impl_.on_publish_done(from_context(tok.get_user_context()),
                                  tok.get_return_code() == 0 ? -1 : tok.get_return_code(),
                                  tok.get_reason_code(), describe_failure(tok));
        }
        Impl& impl_;
    };

    struct ConnectListener final : paho::iaction_listener {
        explicit ConnectListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token&) override {
            impl_.post([](Impl& self) { self.on_connect(true, {}); });
        }
        void on_failure(const paho::token& tok) override {
            impl_.post([reason = describe_failure(tok)](Impl& self) mutable {
                self.on_connect(false, std::move(reason));
            });
        }
        Impl& impl_;
    };

    struct SubscribeListener final : paho::iaction_listener {
        explicit SubscribeListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token&) override {}
        void on_failure(const paho::token& tok) override {
            impl_.post([reason = describe_failure(tok)](Impl& self) {
                spdlog::warn("MQTT subscribe failed on {}: {}", self.options_.url, reason);
            });
        }
        Impl& impl_;
    };

    enum class State { idle, connecting, connected, waiting, stopped };

    const boost::asio::any_io_executor loop_;
    const ClientOptions options_;
    const std::optional<detail::BrokerEndpoint> endpoint_;
    /// QoS >= 1 publications in flight when the connection drops are sent again (see
    /// on_publish_done).
    const bool requeue_in_flight_;

    // Loop-owned.
    State state_ = State::idle;
    boost::asio::steady_timer reconnect_timer_;
    boost::asio::steady_timer loss_hold_timer_;
    detail::ReconnectBackoff backoff_;
    ConnectedHandler on_connected_;
    MessageHandler on_message_;
    std::vector<std::string> subscriptions_;
    core::ThrottledLog connect_failure_log_;

    // Guarded by mutex_ (touched by the loop, the sender, Paho's threads and stop()).
    mutable std::mutex mutex_;
    std::condition_variable wake_sender_;  ///< work and room, or quit
    std::condition_variable completed_;    ///< an in-flight publication finished (for stop())
    PublishQueue queue_;
    PublishQueue batch_queue_;
    bool next_from_batch_ = false;  ///< whose turn when both lanes wait
    /// Sent again before anything else after a reconnect, by original order. A suspect was in
    /// flight when the connection went (see requeue_after_loss); the others never left.
    struct Retry {
        Message message;
        bool suspect = false;
    };
    std::map<std::uint64_t, Retry> retry_;
    std::optional<std::uint64_t> probe_;         ///< the suspect in flight, alone
    bool held_for_reconnect_ = false;            ///< see hold_for_reconnect()
    detail::InFlightWindow<Message> in_flight_;  ///< handed to Paho, not yet completed
    /// Blank messages of completed publications, handed back to publish()'s callers to fill
    /// again: the loop allocated two strings per publication that Paho's thread then freed,
    /// and malloc's cross-thread traffic was 40 % of the loop's time (#6).
    std::vector<Message> spares_;
    bool sending_ = false;          ///< connected and announced: the sender may send
    bool sender_idle_ = false;      ///< the sender waits on wake_sender_
    bool window_full_ = false;      ///< the sender stopped at the limit: wait for the low mark
    bool quit_ = false;             ///< the sender thread must end
    std::size_t backlog_peak_ = 0;  ///< largest queue since memory was last given back
    core::ThrottledLog publish_failure_log_;
    core::ThrottledLog refused_log_;

    /// max_in_flight, lowered to the broker's receive maximum on each connect.
    std::atomic<std::size_t> in_flight_limit_;
    std::atomic<bool> link_up_{false};  ///< Paho's view: set by the loop, cleared by Paho's thread
    std::atomic<bool> connected_{false};  ///< the loop's view, for connected() and stats()
    std::atomic<bool> stopping_{false};
    std::atomic<std::uint64_t> published_{0};
    std::atomic<std::uint64_t> publish_failures_{0};
    std::atomic<std::uint64_t> connects_{0};
    std::atomic<std::uint64_t> connection_losses_{0};
    std::atomic<std::uint64_t> received_{0};
    /// Never handed to Paho because the broker would refuse them, or dropped after the broker
    /// closed the connection on them twice.
    std::atomic<std::uint64_t> refused_{0};
    /// The broker's Maximum Packet Size (MQTT 5 CONNACK), read on each connect.
    std::atomic<std::size_t> max_packet_size_{detail::max_mqtt_packet_size};
    detail::NagleSwitch nagle_;

    PublishListener publish_listener_{*this};
    ConnectListener connect_listener_{*this};
    SubscribeListener subscribe_listener_{*this};
    paho::connect_options connect_options_;
    /// Destroyed before the members above (declared after them), so no Paho callback outlives
    /// what it touches; the sender thread is joined in ~Impl before that.
    std::unique_ptr<paho::async_client> client_;
    paho::token_ptr connect_token_;  ///< loop-owned; read for the CONNACK's properties
    std::thread sender_;
};

Client::Impl::Impl(boost::asio::any_io_executor loop, ClientOptions options)
    : loop_(std::move(loop)),
      options_(std::move(options)),
      endpoint_(detail::parse_broker_url(options_.url)),
      // With a clean session Paho discards unacknowledged publications on reconnect, so we
      // resend them; with a kept session Paho resends them itself and we must not duplicate.
      requeue_in_flight_(options_.clean_start ||
                         (options_.version == 5 && options_.session_expiry.count() == 0)),
      reconnect_timer_(loop_),
      loss_hold_timer_(loop_),
      backoff_(options_.min_backoff, options_.max_backoff),
      queue_(options_.buffer_max_messages),
      batch_queue_(options_.batch_lane_max_messages),
      in_flight_limit_(std::max<std::size_t>(1, options_.max_in_flight)) {
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
        spdlog::warn("MQTT url {} is not ssl:// or wss://: mqtt.tls is ignored", options_.url);
    }

    // Paho's threads: copy, count, post; nothing else.
    client_->set_connection_lost_handler([this](const std::string& cause) {
        link_up_ = false;
        post([cause](Impl& self) { self.on_connection_lost(cause.empty() ? "unknown" : cause); });
    });
    client_->set_disconnected_handler([this](const paho::properties&, paho::ReasonCode reason) {
        link_up_ = false;
        post([reason](Impl& self) {
            self.on_connection_lost("broker sent DISCONNECT: " +
                                    paho::exception::reason_code_str(reason));
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
        connect_token_ = client_->connect(connect_options_, nullptr, connect_listener_);
    } catch (const paho::exception& e) {
        on_connect(false, e.what());
    }
}

void Client::Impl::on_connect(bool ok, std::string reason) {
    if (state_ != State::connecting) {
        return;  // stopped meanwhile
    }
    if (ok && !client_->is_connected()) {
        ok = false;  // lost again before this ran
        reason = "connection lost right after connect";
    }
    if (!ok) {
        reason = explain_connect_failure(std::move(reason));
        if (const auto count = connect_failure_log_.record(Clock::now())) {
            if (count == 1) {
                spdlog::warn("MQTT cannot connect to {}: {}", options_.url, reason);
            } else {
                spdlog::warn("MQTT cannot connect to {}: {} ({} failed attempts)", options_.url,
                             reason, count);
            }
            spdlog::info("MQTT reconnecting in {} ms", schedule_reconnect().count());
        } else {
            schedule_reconnect();
        }
        return;
    }

    state_ = State::connected;
    link_up_ = true;
    connected_ = true;
    connects_.fetch_add(1, std::memory_order_relaxed);
    backoff_.reset();
    update_in_flight_limit();
    connect_failure_log_.reset();
    spdlog::info("MQTT connected to {}", options_.url);

    if (endpoint_) {
        nagle_.attach(detail::sockets_connected_to(endpoint_->host, endpoint_->port));
    }
    // Subscribe before announcing `online`: the broker handles one connection's packets in
    // order, so whoever sees `online` can already write to us.
    renew_subscriptions(subscriptions_);
    try {
        if (!options_.availability_topic.empty()) {
            client_->publish(paho::make_message(options_.availability_topic, "online",
                                                options_.availability_qos, true));
        }
    } catch (const paho::exception& e) {
        spdlog::warn("MQTT cannot publish availability: {}", e.what());
    }
    if (on_connected_) {
        on_connected_();
    }
    set_sending(true);
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
    // not hand it more. (The token the listener sees lacks the CONNACK properties in Paho C++
    // 1.2; the one connect() returned has them.)
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
    if (!options_.availability_topic.empty() && receive_maximum > 1) {
        --receive_maximum;  // room for `online` and `offline`
    }
    in_flight_limit_ = std::max<std::size_t>(1, std::min(options_.max_in_flight, receive_maximum));
}

void Client::Impl::on_connection_lost(std::string cause) {
    if (state_ != State::connected) {
        return;
    }
    connected_ = false;
    connection_losses_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("MQTT connection to {} lost: {}", options_.url, cause);
    nagle_.detach();
    std::string dropped;
    {
        // Whatever Paho did not confirm is either sent again (QoS >= 1, clean session) or
        // counted as failed. Completions arriving later find nothing and are ignored, so
        // nothing is counted twice.
        std::lock_guard lock(mutex_);
        sending_ = false;
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
    spdlog::info("MQTT reconnecting in {} ms", schedule_reconnect().count());
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
        spdlog::warn("MQTT subscribe failed on {}: {}", options_.url, e.what());
    }
}

// --- publications ------------------------------------------------------------------------

void Client::Impl::enqueue(Message& message) {
    bool wake = false;
    {
        std::lock_guard lock(mutex_);
        (message.batch_lane ? batch_queue_ : queue_).push(std::move(message));
        // Queued whole, so no buffer came back: give the caller a spare to fill next time.
        const std::size_t inline_capacity = std::string().capacity();
        if (message.topic.capacity() <= inline_capacity &&
            message.payload.capacity() <= inline_capacity && !spares_.empty()) {
            message = std::move(spares_.back());
            spares_.pop_back();
        }
        backlog_peak_ = std::max(backlog_peak_, queue_.size());
        wake = sender_idle_ && ready_to_send();
    }
    if (wake) {
        wake_sender_.notify_one();
    }
}

void Client::Impl::recycle(Message&& message) {
    // A window's worth is what cycles (more only held memory after an overload: bench
    // scenario 8 peaked 0.3 MB higher with 1,024); a drained backlog's others are freed.
    if (spares_.size() >= in_flight_limit_.load(std::memory_order_relaxed)) return;
    message.clear();
    spares_.push_back(std::move(message));
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
    const std::size_t limit = in_flight_limit_.load(std::memory_order_relaxed);
    return in_flight_.pending() <=
           (window_full_ ? limit - std::max<std::size_t>(1, limit / 8) : limit - 1);
}

bool Client::Impl::take_next(Message& message) {
    bool from_batch = !batch_queue_.empty();
    if (from_batch && !queue_.empty()) {
        from_batch = next_from_batch_;
        next_from_batch_ = !next_from_batch_;
    }
    auto next = (from_batch ? batch_queue_ : queue_).pop();
    if (!next) {
        return false;
    }
    message = std::move(*next);
    return true;
}

void Client::Impl::sender_main() {
    struct Outgoing {
        std::uint64_t id;
        paho::message_ptr message;
    };
    // Named for `top -H` and profiles (at most 15 characters).
    ::pthread_setname_np(::pthread_self(), "mqtt-sender");
    std::vector<Outgoing> burst;
    std::unique_lock lock(mutex_);
    for (;;) {
        sender_idle_ = true;
        wake_sender_.wait(lock, [this] { return quit_ || ready_to_send(); });
        sender_idle_ = false;
        if (quit_) {
            return;
        }
        // Take a burst under the lock (Paho copies topic and payload in make_message, so the
        // window keeps our Message only for a re-send), then publish it without the lock.
        const std::size_t limit = in_flight_limit_;
        const std::size_t max_packet_size = max_packet_size_;
        Message message;
        std::string refused_topic;
        std::string refused_problem;
        while (in_flight_.pending() < limit) {
            if (suspect_waits()) break;
            bool probe = false;
            if (!retry_.empty()) {
                auto retry = std::move(retry_.extract(retry_.begin()).mapped());
                message = std::move(retry.message);
                probe = retry.suspect;
            } else if (!take_next(message)) {
                break;
            }
            if (auto problem = detail::publication_problem(message, max_packet_size);
                !problem.empty()) {
                refused_.fetch_add(1, std::memory_order_relaxed);
                refused_topic = std::move(message.topic);
                refused_problem = std::move(problem);
                recycle(std::move(message));
                continue;
            }
            auto out =
                paho::make_message(message.topic, message.payload, message.qos, message.retain);
            if (!message.correlation_data.empty() && options_.version == 5) {
                out->set_properties(
                    paho::properties{{paho::property::CORRELATION_DATA, message.correlation_data}});
            }
            const auto id = in_flight_.add(std::move(message));
            burst.push_back({id, std::move(out)});
            if (probe) {
                probe_ = id;
                break;
            }
        }
        window_full_ = in_flight_.pending() >= limit;
        const bool backlog = window_full_ && has_queued();
        // A large backlog (the first publication of every tag, a reconnect's republish, an
        // outage's buffer) leaves its freed messages in malloc's arenas: once it has drained,
        // give them back, so that resident memory follows the live data.
        const bool trim = !has_queued() && backlog_peak_ >= kTrimAfterBacklog;
        if (trim) {
            backlog_peak_ = 0;
            queue_.release_memory();
            batch_queue_.release_memory();
        }
        lock.unlock();
        if (!refused_topic.empty()) log_refused(refused_topic, refused_problem);
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
        "MQTT publication to {} failed again when it was sent alone (the broker closed the "
        "connection on it, or Paho refused it): it is dropped, so that it cannot block every "
        "connection after",
        core::printable(topic));
}

void Client::Impl::log_refused(const std::string& topic, const std::string& problem) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = refused_log_.record(Clock::now());
    }
    if (count > 0) {
        spdlog::error(
            "MQTT publication to {} dropped: a broker would refuse it ({}) and close the "
            "connection ({} dropped since last report)",
            core::printable(topic), problem, count);
    }
}

void Client::Impl::log_publish_failure(const std::string& topic, const std::string& reason) {
    std::uint64_t count = 0;
    {
        std::lock_guard lock(mutex_);
        count = publish_failure_log_.record(Clock::now());
    }
    if (count > 0) {
        spdlog::warn("MQTT publish to {} failed: {} ({} failures since last report)", topic, reason,
                     count);
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
            lost = queue_.size() + batch_queue_.size() + retry_.size();
        }
        end_sender();
        if (lost > 0) {
            spdlog::warn("MQTT stopping while disconnected: {} queued publications dropped", lost);
        }
        connected_ = false;
        return;
    }

    paho::delivery_token_ptr offline;
    try {
        if (!options_.availability_topic.empty()) {
            offline = client_->publish(paho::make_message(options_.availability_topic, "offline",
                                                          options_.availability_qos, true));
        }
    } catch (const paho::exception& e) {
        spdlog::warn("MQTT cannot publish availability: {}", e.what());
    }

    std::size_t unsent = 0;
    {
        std::unique_lock lock(mutex_);
        completed_.wait_until(lock, deadline,
                              [this] { return !has_queued() && in_flight_.empty(); });
        unsent = queue_.size() + batch_queue_.size() + retry_.size() + in_flight_.pending();
    }
    end_sender();
    if (offline) {
        const auto left = std::max(Clock::duration::zero(), deadline - Clock::now());
        try {
            offline->wait_for(std::chrono::duration_cast<std::chrono::milliseconds>(left));
        } catch (const paho::exception&) {
        }
    }
    if (unsent > 0) {
        spdlog::warn("MQTT stop: {} publications not confirmed within {} ms", unsent,
                     flush_timeout.count());
    }
    try {
        client_->disconnect(paho::disconnect_options(std::chrono::seconds(1)))
            ->wait_for(std::chrono::seconds(2));
    } catch (const paho::exception& e) {
        spdlog::warn("MQTT disconnect failed: {}", e.what());
    }
    link_up_ = false;
    connected_ = false;
    spdlog::info("MQTT disconnected from {}", options_.url);
}

// --- Client ------------------------------------------------------------------------------

Client::Client(boost::asio::any_io_executor loop, ClientOptions options)
    : impl_(std::make_shared<Impl>(std::move(loop), std::move(options))) {}

Client::~Client() = default;

void Client::set_on_connected(ConnectedHandler handler) {
    impl_->on_connected_ = std::move(handler);
}

void Client::set_on_message(MessageHandler handler) { impl_->on_message_ = std::move(handler); }

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
            spdlog::warn("MQTT unsubscribe failed on {}: {}", impl.options_.url, e.what());
        }
    }
}

void Client::start() {
    if (impl_->state_ == Impl::State::idle) {
        impl_->do_connect();
    }
}

void Client::publish(Message&& message) { impl_->enqueue(message); }

void Client::stop(std::chrono::milliseconds flush_timeout) { impl_->stop(flush_timeout); }

bool Client::connected() const { return impl_->connected_; }

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
    std::lock_guard lock(impl.mutex_);
    s.queued = impl.queue_.size() + impl.batch_queue_.size() + impl.retry_.size();
    s.in_flight = impl.in_flight_.pending();
    s.dropped_overflow = impl.queue_.dropped_overflow() + impl.batch_queue_.dropped_overflow();
    s.coalesced = impl.queue_.coalesced();
    return s;
}

void Client::set_buffer_capacity(std::size_t max_messages) {
    std::lock_guard lock(impl_->mutex_);
    impl_->queue_.set_capacity(max_messages);
}

}  // namespace eip2mqtt::adapters::mqtt
