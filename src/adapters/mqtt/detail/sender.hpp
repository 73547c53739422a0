#pragma once
/// The sender: a thread of the client's own that hands queued publications to Paho, and what
/// Paho tells of them afterwards (completed, failed, refused), kept in a SendLedger: the
/// outbox, the in-flight window, retries and suspects, the client's own publications' slots.
///
/// Why a thread: Paho C writes to its socket under one global mutex, and a loop waiting on it
/// would neither drain UDP nor keep production deadlines. enqueue() only queues (a short lock)
/// and wakes the thread when it sleeps.
///
/// Its parts, each in its own file: the SendLedger (what waits and what is in flight), the
/// SenderSignals (sleeping and waking), the SenderCounters and the SenderLog (failures). Its
/// own files: sender.cpp (queueing, the connection's events, the client's own publications,
/// stop()'s steps) and sender_publish.cpp (a publication's way through Paho: the thread that
/// hands it over, what Paho answers, the requeue after a lost connection).
///
/// Threading: the ledger and the signals are guarded by mutex_, held for the ledger only,
/// never across a Paho call. enqueue() and the stop steps run on any thread; the thread runs
/// sender_main; Paho's threads run the listeners (completions, under mutex_); the connection's
/// events (set_sending, on_connected, on_connection_lost) and the handler and timer run on the
/// loop, except set_link_up(false), which Paho's thread calls when it sees the link go.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mqtt/async_client.h>

#include <atomic>
#include <boost/asio/steady_timer.hpp>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "adapters/mqtt/detail/loop_post.hpp"
#include "adapters/mqtt/detail/paho_tokens.hpp"
#include "adapters/mqtt/detail/publish_properties.hpp"
#include "adapters/mqtt/detail/send_ledger.hpp"
#include "adapters/mqtt/detail/sender_counters.hpp"
#include "adapters/mqtt/detail/sender_log.hpp"
#include "adapters/mqtt/detail/sender_signals.hpp"
#include "adapters/mqtt/detail/tcp_nodelay.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class Sender {
public:
    using AcknowledgedHandler = std::function<void(std::uint64_t ack_token)>;

    /// `paho`, `loop` and `nagle` outlive it; the thread starts with start_thread().
    Sender(const ClientOptions& options, ::mqtt::async_client& paho, const LoopPost& loop,
           NagleSwitch& nagle);
    ~Sender();
    Sender(const Sender&) = delete;
    Sender& operator=(const Sender&) = delete;

    void start_thread();

    // --- any thread ------------------------------------------------------------------------
    /// Queues `message` in its lane and wakes the thread if it sleeps.
    void enqueue(Message& message);
    /// A publication dropped before it was queued (session-bound, while disconnected).
    void count_discarded() { SenderCounters::bump(counters_.discarded); }
    void set_buffer_capacity(std::size_t max_messages);
    void set_batch_first(bool batch_first);
    /// The broker's Maximum Packet Size for the current connection (see Client).
    std::size_t max_packet_size() const { return max_packet_size_; }
    /// Fills the publication fields of `stats`.
    void add_stats(ClientStats& stats) const;
    /// Paho's view: false once Paho reported the link gone (any thread), true on a connect.
    void set_link_up(bool up) { link_up_ = up; }
    bool link_up() const { return link_up_; }

    // --- the connection's events, on the loop ----------------------------------------------
    void set_on_acknowledged(AcknowledgedHandler handler) { on_acknowledged_ = std::move(handler); }
    /// A connect: the broker's Receive Maximum and Maximum Packet Size (unchanged when the
    /// CONNACK could not be read), and a fresh count of the own publications' slots.
    void on_connected(std::size_t receive_maximum, std::optional<std::size_t> max_packet_size,
                      std::uint16_t topic_alias_maximum = 0);
    /// Publications sent by topic alias alone (ClientOptions::topic_aliases).
    std::uint64_t aliased() const { return properties_.aliased(); }
    /// Lets the thread hand publications to Paho (once announced), or stops it.
    void set_sending(bool enabled);
    /// What was in flight is sent again (QoS >= 1, a clean session) or counted as failed; a
    /// session-bound client drops what waits.
    void on_connection_lost();
    /// After on_connection_lost(): returns once the thread hands nothing more to Paho, the
    /// burst it took before sending stopped handed over whole (microseconds: Paho only queues
    /// each publication). What the caller publishes to Paho next comes after all of it.
    void wait_idle();

    // --- the client's own publications (online, offline) -----------------------------------
    /// Takes a slot of the acknowledged window; returns the connection's generation.
    std::uint64_t reserve_own_slot();
    /// Publishes outside the queues; at QoS >= 1 in the slot reserved for `generation`, given
    /// back when the broker answers. Throws what Paho throws.
    ::mqtt::delivery_token_ptr publish_own(::mqtt::message_ptr message, std::uint64_t generation);

    // --- stop()'s steps, on the stopping thread --------------------------------------------
    /// From now on completions wake stop(); false when stopping began before.
    bool begin_stop() { return !stopping_.exchange(true); }
    /// On the loop: no more hold timer.
    void cancel_hold() { hold_timer_.cancel(); }
    /// Waits until the own publications' reserved slots fit in the window, or `deadline`.
    void wait_for_own_slots(core::MonoTime deadline);
    /// Waits until nothing waits or is in flight, or `deadline`; returns how many are left.
    std::size_t flush(core::MonoTime deadline);
    /// Publications waiting (dropped by a stop while disconnected).
    std::size_t queued() const;
    /// Ends the thread (idempotent).
    void end_thread();

private:
    /// A publication taken for a burst, with Paho's message built outside mutex_.
    struct Taken {
        Message message;
        bool probe = false;
        ::mqtt::message_ptr out;  ///< none when a broker would refuse it
    };
    struct Outgoing {
        std::uint64_t id;
        ::mqtt::message_ptr message;
    };

    struct PublishListener final : ::mqtt::iaction_listener {
        explicit PublishListener(Sender& sender) : sender_(sender) {}
        void on_success(const ::mqtt::token& tok) override;
        void on_failure(const ::mqtt::token& tok) override;
        Sender& sender_;
    };
    /// For the own publications: the context is the connection's generation.
    struct OwnPublicationListener final : ::mqtt::iaction_listener {
        explicit OwnPublicationListener(Sender& sender) : sender_(sender) {}
        void on_success(const ::mqtt::token& tok) override;
        void on_failure(const ::mqtt::token& tok) override;
        Sender& sender_;
    };

    // sender.cpp
    void release_own_slot(std::uint64_t generation);

    // sender_publish.cpp: the thread
    bool ready_to_send() const;  ///< under mutex_
    void sender_main();
    void take_burst(std::vector<Taken>& taken);     ///< under mutex_
    void prepare_burst(std::vector<Taken>& taken);  ///< without mutex_: the costly part
    /// Under mutex_: into the window, in order; returns whether the window stopped a backlog.
    bool admit_burst(std::vector<Taken>& taken, std::vector<Outgoing>& burst);
    void send(std::uint64_t id, const ::mqtt::message_ptr& message);
    ::mqtt::message_ptr to_paho(const Message& message);

    // sender_publish.cpp: what Paho answers
    /// Publication `id` completed with Paho return code `rc` and, when the broker refused it
    /// (MQTT 5), its reason code (>= 0x80).
    void on_publish_done(std::uint64_t id, int rc, int reason_code, const std::string& reason);
    /// A synchronous refusal of Paho's (send()).
    void on_send_refused(std::uint64_t id, const ::mqtt::message_ptr& message,
                         const ::mqtt::exception& e);
    /// Whether a failure is the broker's own verdict: an MQTT 5 PUBACK with a failure reason
    /// code on a live connection. MQTT 3.1.1 has none; Paho's own failures carry other codes.
    bool broker_refused(int rc, int reason_code) const;

    // sender_publish.cpp: the requeue after a loss
    /// Under mutex_: the hold (SendLedger::hold) and a requeued suspect; returns the topic of a
    /// dropped one.
    std::string requeue_after_loss(std::uint64_t id, Message&& message);
    /// Under mutex_: Paho reports a loss's failures before its connection-lost handler runs, so
    /// the thread holds everything until the next connect, lest a suspect be sent "alone" on
    /// the dying connection and be blamed for a loss it did not cause. Should the connection
    /// survive, the hold ends after kLossHold.
    void hold_for_reconnect();

    const ClientOptions& options_;
    ::mqtt::async_client& paho_;
    const LoopPost& loop_;
    NagleSwitch& nagle_;
    /// With a clean session Paho discards unacknowledged publications on reconnect, so we send
    /// them again; with a kept session Paho does, and we must not duplicate.
    const bool requeue_in_flight_;

    // The loop's.
    AcknowledgedHandler on_acknowledged_;
    boost::asio::steady_timer hold_timer_;

    // Guarded by mutex_.
    mutable std::mutex mutex_;
    SenderSignals signals_;
    SendLedger ledger_;
    bool sending_ = false;  ///< connected and announced

    SenderLog log_;
    std::atomic<bool> link_up_{false};
    std::atomic<bool> stopping_{false};
    std::atomic<std::size_t> max_packet_size_;
    SenderCounters counters_;
    PublishProperties properties_;  ///< the sender thread's, but for on_connected

    PublishListener publish_listener_{*this};
    OwnPublicationListener own_publication_listener_{*this};
    std::thread thread_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
