#pragma once
/// The pair's own MQTT connection (docs/redundancy.md), as the Pair uses it: it publishes and
/// subscribes (a Publisher), says when it is connected, hands what it hears and what the broker
/// acknowledged, starts and stops. The real one is an adapters::mqtt::Client with the options
/// of pair_client_options (mqtt_pair_connector); a test hands the Pair a fake broker.
///
/// Threading: the loop, but for stop() (as adapters::mqtt::Client's).

#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"

namespace eip2mqtt::core::config {
struct Config;
}

namespace eip2mqtt::app::redundancy {

class PairConnection : public adapters::mqtt::Publisher {
public:
    using Connected = std::function<void()>;
    using Heard = std::function<void(adapters::mqtt::Incoming)>;
    using Acknowledged = std::function<void(std::uint64_t ack_token)>;

    /// Runs after every (re)connect.
    virtual void set_on_connected(Connected handler) = 0;
    /// Runs for every message heard on a subscription (the pair hears its own records).
    virtual void set_on_message(Heard handler) = 0;
    /// Runs with the `ack_token` of each publication the broker acknowledged.
    virtual void set_on_acknowledged(Acknowledged handler) = 0;
    /// Starts connecting; retries until stop().
    virtual void start() = 0;
    /// Waits up to `flush_timeout` for what is queued, then disconnects (its will then clears
    /// the leader topic). Blocks the calling thread.
    virtual void stop(std::chrono::milliseconds flush_timeout) = 0;
    virtual bool connected() const = 0;
};

/// Makes the pair's connection of `config`, whose last will is `will`.
using PairConnector = std::function<std::unique_ptr<PairConnection>(
    const core::config::Config& config, adapters::mqtt::Message will)>;

/// Options of the pair's connection: the same broker, credentials and TLS as the gateway's,
/// client id `{client id}-pair`, a clean session, session-bound (a renewal queued while
/// disconnected would be stale when sent), `will` its last will. Its own connection, so that a
/// renewal never waits behind the tag tree's queue.
adapters::mqtt::ClientOptions pair_client_options(const core::config::Config& config,
                                                  adapters::mqtt::Message will);

/// The real connection: an adapters::mqtt::Client on `loop`, with pair_client_options.
PairConnector mqtt_pair_connector(boost::asio::any_io_executor loop);

}  // namespace eip2mqtt::app::redundancy
