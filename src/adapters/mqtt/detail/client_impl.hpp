#pragma once
/// Client::Impl, shared by the files that implement it: client_connection.cpp (connect,
/// reconnect, subscriptions) and client_publications.cpp (the sender thread and what is in
/// flight). One class, two concerns, each in a file of its own.

#include <mqtt/async_client.h>
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
#include "adapters/mqtt/detail/connection_reasons.hpp"
#include "adapters/mqtt/detail/in_flight_window.hpp"
#include "adapters/mqtt/detail/outbox.hpp"
#include "adapters/mqtt/detail/publication_check.hpp"
#include "adapters/mqtt/detail/reconnect_backoff.hpp"
#include "adapters/mqtt/detail/tcp_nodelay.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/printable.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::mqtt {

namespace paho = ::mqtt;

namespace detail {

/// How long the sender holds after a loss-like failure if the connection does not go meanwhile.
inline constexpr auto kLossHold = std::chrono::seconds(1);
inline constexpr auto kConnectTimeout = std::chrono::seconds(10);
/// Queued publications past which the memory of a drained backlog is given back (malloc_trim
/// walks every arena: worth it after a burst, not after every message).
inline constexpr std::size_t kTrimAfterBacklog = 10000;

inline std::string describe_failure(const paho::token& tok) {
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

inline void* to_context(std::uint64_t id) {
    return reinterpret_cast<void*>(static_cast<std::uintptr_t>(id));
}
inline std::uint64_t from_context(void* ctx) { return reinterpret_cast<std::uintptr_t>(ctx); }

}  // namespace detail

using Clock = std::chrono::steady_clock;

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
    /// `return_code`: Paho's, on a failure (a CONNACK's code or reason code, or an error < 0).
    void on_connect(bool ok, std::string reason, int return_code = 0);
    /// Logs a failed attempt (throttled), with what the broker's refusal means, and retries.
    void on_connect_failed(std::string reason, int return_code);
    /// `silent`: Paho gave no cause (no DISCONNECT came; the socket closed or failed).
    void on_connection_lost(std::string cause, bool silent = false);
    /// Adds what connect_token_ knows and, over TLS, what to check, to a generic reason.
    std::string explain_connect_failure(std::string reason) const;
    void update_in_flight_limit();
    /// Arms the backoff timer; returns the delay.
    std::chrono::milliseconds schedule_reconnect();
    void renew_subscriptions(const std::vector<std::string>& filters);

    // --- any thread ----------------------------------------------------------------------
    /// Queues `message` in its lane and wakes the sender if it sleeps.
    void enqueue(Message& message);
    /// Paho's message for `message` (topic, payload and, over MQTT 5, its properties).
    paho::message_ptr to_paho(const Message& message) const;
    /// Keeps a completed publication's buffers (Outbox::recycle), a window's worth at most.
    void recycle(Message&& message);
    /// Lets the sender hand publications to Paho (after a connect) or stops it (loss, stop).
    void set_sending(bool enabled);
    /// A Paho listener: publication `id` completed with Paho return code `rc` and, when the
    /// broker refused it (MQTT 5), its reason code (>= 0x80).
    void on_publish_done(std::uint64_t id, int rc, int reason_code, const std::string& reason);
    /// Takes a slot of the acknowledged window for one of the client's own QoS >= 1
    /// publications (`online`, `offline`), under mutex_; returns the connection's generation,
    /// which publish_own and its listener carry.
    std::uint64_t reserve_own_slot();
    /// Publishes one of the client's own messages outside the queues; at QoS >= 1 in the slot
    /// reserve_own_slot() took for `generation`, given back when the broker answers.
    paho::delivery_token_ptr publish_own(paho::message_ptr message, std::uint64_t generation);
    /// The slot of an own publication of connection `generation` is free again.
    void release_own_slot(std::uint64_t generation);
    void log_publish_failure(const std::string& topic, const std::string& reason);
    void stop(std::chrono::milliseconds flush_timeout);

    // --- sender thread -------------------------------------------------------------------
    /// A publication the sender took from the queues, with what it made of it without mutex_.
    struct Taken {
        Message message;
        bool probe = false;     ///< a suspect, sent alone
        paho::message_ptr out;  ///< Paho's message; none when a broker would refuse it
    };
    struct Outgoing {
        std::uint64_t id;
        paho::message_ptr message;
    };
    void sender_main();
    /// Under mutex_: moves the next publications the windows have room for into `taken`,
    /// counted in taking_ meanwhile.
    void take_burst(std::vector<Taken>& taken);
    /// Without mutex_: checks each taken publication and builds its Paho message, the costly
    /// part (allocations and copies) that Paho's threads would otherwise wait for.
    void prepare_burst(std::vector<Taken>& taken);
    /// Under mutex_: adds the prepared publications to the window, in order, into `burst`;
    /// recycles the refused ones. Returns whether the sender stopped on a backlog.
    bool admit_burst(std::vector<Taken>& taken, std::vector<Outgoing>& burst);
    /// Paho's publish of one taken message; a synchronous refusal is handled here.
    void send(std::uint64_t id, const paho::message_ptr& message);

    // --- under mutex_ --------------------------------------------------------------------
    bool has_queued() const { return !retry_.empty() || !outbox_.empty(); }
    /// Publications in flight, with those the sender has taken and not yet added (taking_).
    std::size_t pending() const { return in_flight_.pending() + taking_; }
    /// Of pending(), those awaiting an acknowledgement (QoS >= 1).
    std::size_t pending_acknowledged() const {
        return in_flight_.pending_acknowledged() + taking_acknowledged_;
    }
    /// Whether the sender has something to send and room to send it (detail/send_room.hpp).
    bool ready_to_send() const;
    /// Whether the next publication the sender would take awaits an acknowledgement (QoS >= 1),
    /// and so needs room under acknowledged_limit_ as well.
    bool next_awaits_ack() const;
    /// A suspect goes alone: nothing else is sent while one is in flight, and one waits until
    /// nothing is in flight.
    bool suspect_waits() const {
        return probe_.has_value() || held_for_reconnect_ ||
               (!retry_.empty() && retry_.begin()->second.suspect && pending() != 0);
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
            impl_.on_publish_done(detail::from_context(tok.get_user_context()), 0, 0, {});
        }
        void on_failure(const paho::token& tok) override {
            impl_.on_publish_done(detail::from_context(tok.get_user_context()),
                                  tok.get_return_code() == 0 ? -1 : tok.get_return_code(),
                                  tok.get_reason_code(), detail::describe_failure(tok));
        }
        Impl& impl_;
    };

    /// For the client's own publications: the context is the connection's generation.
    struct OwnPublicationListener final : paho::iaction_listener {
        explicit OwnPublicationListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token& tok) override {
            impl_.release_own_slot(detail::from_context(tok.get_user_context()));
        }
        void on_failure(const paho::token& tok) override {
            impl_.release_own_slot(detail::from_context(tok.get_user_context()));
        }
        Impl& impl_;
    };

    struct ConnectListener final : paho::iaction_listener {
        explicit ConnectListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token&) override {
            impl_.post([](Impl& self) { self.on_connect(true, {}); });
        }
        void on_failure(const paho::token& tok) override {
            impl_.post([reason = detail::describe_failure(tok), rc = tok.get_return_code()](
                           Impl& self) mutable { self.on_connect(false, std::move(reason), rc); });
        }
        Impl& impl_;
    };

    struct SubscribeListener final : paho::iaction_listener {
        explicit SubscribeListener(Impl& impl) : impl_(impl) {}
        void on_success(const paho::token&) override {}
        void on_failure(const paho::token& tok) override {
            impl_.post([reason = detail::describe_failure(tok)](Impl& self) {
                spdlog::warn("{} subscribe failed on {}: {}", self.options_.log_name,
                             self.options_.url, reason);
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
    AcknowledgedHandler on_acknowledged_;
    std::vector<std::string> subscriptions_;
    core::ThrottledLog connect_failure_log_;
    Clock::time_point connected_at_{};
    detail::SilentLossPattern silent_losses_;

    // Guarded by mutex_ (touched by the loop, the sender, Paho's threads and stop()).
    mutable std::mutex mutex_;
    std::condition_variable wake_sender_;  ///< work and room, or quit
    std::condition_variable completed_;    ///< an in-flight publication finished (for stop())
    detail::Outbox outbox_;  ///< re-sent publications are taken by the sender itself (retry_)
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
    bool sending_ = false;                       ///< connected and announced: the sender may send
    bool sender_idle_ = false;                   ///< the sender waits on wake_sender_
    bool window_full_ = false;  ///< the sender stopped at the limit: wait for the low mark
    /// Taken from the queues by the sender and not yet in in_flight_ (take_burst to
    /// admit_burst): counted as in flight, so that neither window nor stop() misses them.
    std::size_t taking_ = 0;
    std::size_t taking_acknowledged_ = 0;
    /// The client's own QoS >= 1 publications the broker has not acknowledged on the connection
    /// of generation own_generation_ (one per connect): they share acknowledged_limit_.
    std::size_t own_unacknowledged_ = 0;
    std::uint64_t own_generation_ = 0;
    bool quit_ = false;                 ///< the sender thread must end
    std::optional<Message> last_will_;  ///< options_.will's for the current connection
    core::ThrottledLog publish_failure_log_;
    core::ThrottledLog refused_log_;

    /// Publications in flight, at any QoS: max_in_flight.
    std::atomic<std::size_t> in_flight_limit_;
    /// Of which QoS >= 1: max_in_flight, lowered to the broker's Receive Maximum on each connect.
    /// Paho C holds QoS 0 to no such limit, and at QoS 0 a window of Mosquitto's default 20
    /// woke the sender every other publication and cost a quarter of the rate (#17).
    std::atomic<std::size_t> acknowledged_limit_;
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
    std::atomic<std::uint64_t> discarded_{0};  ///< session_bound: of a connection that went
    /// The broker's Maximum Packet Size (MQTT 5 CONNACK), read on each connect.
    std::atomic<std::size_t> max_packet_size_{detail::max_mqtt_packet_size};
    detail::NagleSwitch nagle_;

    PublishListener publish_listener_{*this};
    OwnPublicationListener own_publication_listener_{*this};
    ConnectListener connect_listener_{*this};
    SubscribeListener subscribe_listener_{*this};
    paho::connect_options connect_options_;
    /// Destroyed before the members above (declared after them), so no Paho callback outlives
    /// what it touches; the sender thread is joined in ~Impl before that.
    std::unique_ptr<paho::async_client> client_;
    paho::token_ptr connect_token_;  ///< loop-owned; read for the CONNACK's properties
    std::thread sender_;
};

}  // namespace eip2mqtt::adapters::mqtt
