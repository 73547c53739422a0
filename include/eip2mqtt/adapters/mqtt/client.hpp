#pragma once
/// The gateway's MQTT connection (Paho MQTT C++ underneath; Paho types stay in the .cpp).
///
/// Threading: every public member but stop() and stats() is called on the loop (the executor
/// given at construction), and every handler is invoked there. Publications are handed to Paho
/// by a sender thread of the client's own, never by the loop: Paho C writes to its socket under
/// one global mutex, and a loop waiting on it would neither drain UDP nor keep production
/// deadlines. publish() only queues (a short lock of our own) and wakes the sender when it
/// sleeps. Paho's callbacks run on Paho's threads: a completed publication updates the queue's
/// state under that lock; everything else is copied and posted to the loop.
///
/// Publications go through a PublishQueue (latest value per topic wins, oldest dropped when
/// full, both counted); a bounded number are in flight in Paho at a time, so Paho's own queue
/// never grows without bound (and stays short: Paho C walks its whole command list on every
/// publish). Batch mode's `_values` have a lane of their own (Message::batch_lane), served in
/// turn with the main queue. While disconnected, the queue is the buffer of
/// `mqtt.buffer.max_messages`. Reconnects use exponential backoff, each to the next broker of
/// ClientOptions::urls; after each connect, whichever the broker, subscriptions are renewed,
/// the availability topic gets `online`, and the on_connected handler runs so that the gateway
/// republishes its retained state.

#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::adapters::mqtt {

struct TlsOptions {
    std::string ca_file;
    std::string cert_file;
    std::string key_file;
    bool verify = true;
};

struct ClientOptions {
    /// How its log lines begin ("MQTT connected to ..."), to tell two connections apart.
    std::string log_name = "MQTT";
    /// The brokers, tried in turn: the first at start, the next after a lost connection or a
    /// failed attempt, back to the first after the last. Never empty.
    std::vector<std::string> urls{"tcp://localhost:1883"};
    std::string client_id = "eip2mqtt";
    int version = 5;  ///< 5 or 3 (3.1.1)
    std::string username;
    std::string password;
    std::optional<TlsOptions> tls;
    std::chrono::seconds keepalive{30};
    /// MQTT 5 session expiry; 0 ends the session with the connection. With a non-zero value and
    /// clean_start false, the broker keeps subscriptions and QoS 1 messages while we are away.
    std::chrono::seconds session_expiry{0};
    bool clean_start = true;

    /// Availability (zigbee2mqtt style): `online` retained on connect, `offline` as last will
    /// and before a clean disconnect. Empty topic: none.
    std::string availability_topic;
    int availability_qos = 1;

    /// A last will made anew, on the loop, before every CONNECT (Sparkplug's NDEATH carries a
    /// bdSeq that changes with each connection); a clean stop() publishes the last one made,
    /// after the queue was flushed. Use it or availability_topic, not both.
    std::function<Message()> will;
    /// MQTT 5: every DISCONNECT carries the reason code Disconnect with Will Message (0x04), so
    /// that the broker says the will as well, after the client said it (Sparkplug B 3.0's rule
    /// for the NDEATH). Off, a clean DISCONNECT discards the will.
    bool disconnect_with_will = false;
    /// What was published for one connection means nothing on the next (Sparkplug: sequence
    /// numbers and aliases start again with every birth). Publications made while disconnected
    /// are dropped, and so is what was queued or in flight when the connection went: the
    /// on_connected handler starts on an empty queue.
    bool session_bound = false;
    /// MQTT 5: the subscriptions hear this connection's own publications too (no_local off).
    /// A pair's lease hears its claim come back after whatever the broker queued for it before
    /// (core/redundancy/lease.hpp). MQTT 3.1.1 has no no_local: every connection hears its own.
    bool hear_own = false;
    /// MQTT 5: a retained publication forwarded live keeps its retain flag (so that retained
    /// writes are refused however they come). Off, only what a subscription fetches from the
    /// broker's store says retained: a pair tells its own image sent back live from a copy of
    /// it stored before a restart or a reconnect.
    bool retain_as_published = true;
    /// The QoS of every subscription (writes, commands, a pair's lease): 1, or 0.
    int subscription_qos = 1;
    /// When set, asked of each publication as the sender thread takes it to hand it to Paho
    /// (on that thread: it must be thread-safe and cheap); false drops it, counted in
    /// `discarded`. A pair's leader that lost its lease says no more as leader, whatever waits.
    std::function<bool(const Message&)> may_send;
    /// MQTT 5: every publication says its content type (`application/json`, or `text/plain`
    /// for a Message::text one) and that its payload is UTF-8 (payload format indicator 1).
    bool describe_payloads = false;
    /// MQTT 5: a live value (Message::live) expires on the broker this long after it was
    /// published, for a subscriber that was away; 0: never.
    std::chrono::seconds message_expiry{0};
    /// MQTT 5: topics are given aliases, up to the broker's Topic Alias Maximum, and sent by
    /// alias after their first publication on a connection. Only with clean_start: a kept
    /// session's publications re-sent by Paho on a new connection would name aliases it lost.
    bool topic_aliases = false;

    std::size_t buffer_max_messages = 100000;
    std::size_t batch_lane_max_messages = 1000;  ///< `_values` waiting; oldest dropped beyond
    /// The batch lane is served first whenever both lanes wait (otherwise in turn).
    bool batch_first = false;
    std::size_t max_in_flight = 256;  ///< publications handed to Paho and not yet completed (Paho C
                                      ///< scans its lists per publish: keep it short)
    std::chrono::milliseconds min_backoff{250};
    std::chrono::milliseconds max_backoff{30000};
    /// The time the client reads (backoff, throttled logs, stop()'s deadline), from the loop,
    /// Paho's threads, the sender's and the stopping one: thread-safe; outlives the client.
    const core::Clock* clock = &adapters::clock::system_clock();
};

struct ClientStats {
    bool connected = false;
    std::string broker;           ///< the URL of the current connection's broker; empty while none
    std::uint64_t published = 0;  ///< completed (QoS 0: written; QoS 1: acknowledged)
    std::uint64_t publish_failures = 0;
    std::uint64_t queued = 0;  ///< waiting in the PublishQueue (both lanes)
    std::uint64_t in_flight = 0;
    std::uint64_t dropped_overflow = 0;  ///< oldest dropped because the queue was full
    std::uint64_t coalesced = 0;         ///< replaced by a newer value of the same topic
    std::uint64_t connects = 0;
    std::uint64_t connection_losses = 0;
    std::uint64_t received = 0;  ///< messages received on subscriptions
    /// Dropped by a session_bound client because they belonged to a connection that went, or
    /// refused by ClientOptions::may_send.
    std::uint64_t discarded = 0;
    /// Dropped because a broker would refuse them (a topic or size beyond MQTT's limits), or
    /// after the broker closed the connection twice with one of them alone in flight.
    std::uint64_t refused = 0;
};

class Client final : public Publisher {
public:
    using ConnectedHandler = std::function<void()>;
    using MessageHandler = std::function<void(Incoming)>;
    using AcknowledgedHandler = std::function<void(std::uint64_t ack_token)>;

    Client(boost::asio::any_io_executor loop, ClientOptions options);
    ~Client() override;
    Client(const Client&) = delete;
    Client& operator=(const Client&) = delete;

    /// Runs on the loop after every successful (re)connect, after `online` was published.
    void set_on_connected(ConnectedHandler handler);
    /// Runs on the loop for every message received on a subscription.
    void set_on_message(MessageHandler handler);
    /// Runs on the loop with the `ack_token` of each publication that has one, once the broker
    /// acknowledged it. A publication the connection lost before that is sent again (QoS 1, as
    /// any other) and acknowledged then, or never: its token is never reported as acknowledged.
    void set_on_acknowledged(AcknowledgedHandler handler);
    /// Topic filters (QoS 1) subscribed on every connect; may be changed at any time.
    void set_subscriptions(std::vector<std::string> filters) override;

    /// Starts connecting (non-blocking); retries with backoff until stop() or end_session().
    void start();

    /// Queues a publication; sent when connected, buffered while not. Leaves `message` blank
    /// (Message::clear()), often with the buffers of an earlier publication: a caller that
    /// publishes in a loop fills the same Message again and allocates nothing.
    void publish(Message&& message) override;

    /// For a session_bound client whose session is over (a pair's leader that stepped down):
    /// what waits to be sent is dropped, never flushed; the will made for the current
    /// connection is published, then DISCONNECT (so the broker does not publish it again); no
    /// reconnect until start() again, whose connection makes a new will. An attempt in
    /// progress is cancelled. Returns without waiting for the broker. Nothing when not started.
    void end_session();
    /// For a session_bound client: ends the session as end_session() does, then connects to
    /// the next broker of the list (the same when the list has one), with a new will. A
    /// Sparkplug node whose primary host went offline looks for it there.
    void leave_broker();

    /// Publishes `offline`, waits up to `flush_timeout` for queued and in-flight publications,
    /// then disconnects and ends the sender thread. Blocks the calling thread: call it after
    /// the loop stopped, or from a thread other than the loop.
    void stop(std::chrono::milliseconds flush_timeout);

    bool connected() const;
    /// The largest packet the broker of the current connection takes: its CONNACK's Maximum
    /// Packet Size (MQTT 5), else max_mqtt_packet_bytes. Read on the loop; set before the
    /// on_connected handler runs. A publication over it is never sent (ClientStats::refused).
    std::size_t max_packet_size() const;
    ClientStats stats() const;
    void set_buffer_capacity(std::size_t max_messages);
    /// ClientOptions::batch_first, from the next publication taken on.
    void set_batch_first(bool batch_first);

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace eip2mqtt::adapters::mqtt
