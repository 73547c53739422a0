#pragma once
/// The connection to the broker, on the loop: the state machine (idle, connecting, connected,
/// waiting to reconnect, stopped), the broker of each attempt (ClientOptions::urls in turn: the
/// next after a failed attempt or a lost connection), the reconnect backoff, the subscriptions
/// renewed on every connect, the will made anew before each, and `online` on the availability
/// topic. It tells the Sender when it may send and when what was in flight is lost.
///
/// Its parts, each in its own file: the BrokerList (which broker), the ReconnectTimer (the
/// backoff), the ConnectDiagnosis (what a failure or a loss means), the Subscriptions, the
/// LastWill and the ConnectionCounters. Its own files: connection.cpp (the way up: connect, the
/// CONNACK, subscriptions, `online`) and connection_down.cpp (the way down: failed attempts, lost
/// connections, a session ended on purpose, stop()'s steps).
///
/// Threading: every member runs on the loop, but connected() and add_stats() (any thread), and
/// the stop steps (the stopping thread: the loop may no longer run). Paho's callbacks copy what
/// they learn and post it to the loop. The last will is thread-safe, since stop() reads it off
/// the loop.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mqtt/async_client.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adapters/mqtt/detail/broker_list.hpp"
#include "adapters/mqtt/detail/connect_diagnosis.hpp"
#include "adapters/mqtt/detail/connection_counters.hpp"
#include "adapters/mqtt/detail/last_will.hpp"
#include "adapters/mqtt/detail/loop_post.hpp"
#include "adapters/mqtt/detail/reconnect_timer.hpp"
#include "adapters/mqtt/detail/sender.hpp"
#include "adapters/mqtt/detail/subscriptions.hpp"
#include "adapters/mqtt/detail/tcp_nodelay.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class Connection {
public:
    using ConnectedHandler = std::function<void()>;
    using MessageHandler = std::function<void(Incoming)>;

    /// `paho`, `loop`, `sender` and `nagle` outlive it. Installs Paho's callbacks.
    Connection(const ClientOptions& options, ::mqtt::async_client& paho, const LoopPost& loop,
               Sender& sender, NagleSwitch& nagle);
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;

    // --- the loop --------------------------------------------------------------------------
    void set_on_connected(ConnectedHandler handler) { on_connected_ = std::move(handler); }
    void set_on_message(MessageHandler handler) { on_message_ = std::move(handler); }
    /// Subscribes what is new and unsubscribes what is gone when connected; kept for every
    /// connect after.
    void set_subscriptions(std::vector<std::string> filters);
    /// Starts connecting, when idle: at first, or after end_session().
    void start();
    /// Whether a publication made now is queued: a session-bound client's belongs to the
    /// connection it is made on, so none is while there is none.
    bool accepts_publications() const {
        return !options_.session_bound || state_ == State::connected;
    }
    /// stop() began: no more connects, timers cancelled.
    void on_stopped();
    /// Client::end_session: back to idle, what waits dropped, the will said, DISCONNECT.
    void end_session();
    /// Client::leave_broker: end_session(), then a connect to the next broker of the list.
    void leave_broker();

    // --- any thread ------------------------------------------------------------------------
    bool connected() const { return counters_.connected; }
    /// Fills the connection fields of `stats`.
    void add_stats(ClientStats& stats) const;

    // --- stop()'s steps, on the stopping thread --------------------------------------------
    /// Whether Paho still has a link to the broker.
    bool link_alive() const;
    /// Publishes the will made for the current connection, if any, ourselves: stop() says it
    /// last, after the flush (Sparkplug's NDEATH must come after everything else). The token
    /// to wait for; none without a will or when Paho refused it.
    ::mqtt::delivery_token_ptr publish_last_will();
    /// Publishes the `offline` availability, if there is one; the token to wait for, if any.
    ::mqtt::delivery_token_ptr publish_offline(core::MonoTime deadline);
    /// A clean DISCONNECT (the broker then publishes no will, unless disconnect_with_will).
    void disconnect();
    void mark_disconnected() { counters_.connected = false; }

private:
    /// `ending`: end_session() asked Paho to disconnect, which has not finished; a start()
    /// meanwhile connects once it has (Paho takes no CONNECT before).
    enum class State { idle, connecting, connected, waiting, ending, stopped };

    struct ConnectListener final : ::mqtt::iaction_listener {
        explicit ConnectListener(Connection& connection) : connection_(connection) {}
        void on_success(const ::mqtt::token& tok) override;
        void on_failure(const ::mqtt::token& tok) override;
        Connection& connection_;
    };
    struct DisconnectListener final : ::mqtt::iaction_listener {
        explicit DisconnectListener(Connection& connection) : connection_(connection) {}
        void on_success(const ::mqtt::token& tok) override;
        void on_failure(const ::mqtt::token& tok) override;
        Connection& connection_;
    };

    // connection.cpp: the way up
    void install_callbacks();
    void on_message_arrived(const ::mqtt::const_message_ptr& msg);
    void do_connect();
    /// `return_code`: Paho's, on a failure (a CONNACK's code or reason code, or an error < 0).
    void on_connect(bool ok, std::string reason, int return_code = 0);
    /// The connection is up: counts, limits, subscriptions, `online`, the handler, sending.
    void on_connected();
    /// Reads the CONNACK's Receive Maximum and Maximum Packet Size into the Sender.
    void apply_broker_limits();
    void announce_online();

    // connection_down.cpp: the way down
    /// Logs a failed attempt (throttled), with what the broker's refusal means, and retries.
    void on_connect_failed(std::string reason, int return_code);
    /// `silent`: Paho gave no cause (no DISCONNECT came; the socket closed or failed).
    void on_connection_lost(std::string cause, bool silent = false);
    /// Paho finished the disconnect of end_session(): idle, or connecting if start() came.
    void on_session_ended();
    /// A DISCONNECT's options: its timeout, and with ClientOptions::disconnect_with_will over
    /// MQTT 5 the reason code that makes the broker say the will.
    ::mqtt::disconnect_options disconnect_options(std::chrono::seconds timeout) const;
    /// Arms the backoff timer; returns the delay.
    std::chrono::milliseconds schedule_reconnect();

    const ClientOptions& options_;
    ::mqtt::async_client& paho_;
    const LoopPost& loop_;
    Sender& sender_;
    NagleSwitch& nagle_;
    BrokerList brokers_;

    // The loop's.
    State state_ = State::idle;
    bool start_pending_ = false;  ///< start() while ending
    ReconnectTimer reconnect_;
    ConnectDiagnosis diagnosis_;
    Subscriptions subscriptions_;
    ConnectedHandler on_connected_;
    MessageHandler on_message_;
    ::mqtt::connect_options connect_options_;
    ::mqtt::token_ptr connect_token_;  ///< read for the CONNACK's properties

    LastWill last_will_;  ///< options_.will's for the current connection
    ConnectionCounters counters_;

    ConnectListener connect_listener_{*this};
    DisconnectListener disconnect_listener_{*this};
};

}  // namespace eip2mqtt::adapters::mqtt::detail
