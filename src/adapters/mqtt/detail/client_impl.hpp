#pragma once
/// Client::Impl: the parts of a Client, in the order they are made (options, loop, Paho, the
/// Sender, the Connection), and stop() as a sequence of named steps over them.
///
/// Threading: the parts say their own. Impl is shared with the work its parts post to the loop
/// (detail/loop_post.hpp), so it lives while such work runs; its destructor ends the sender's
/// thread and Paho's callbacks before any part dies.

#include <mqtt/async_client.h>

#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <memory>

#include "adapters/mqtt/detail/connection.hpp"
#include "adapters/mqtt/detail/loop_post.hpp"
#include "adapters/mqtt/detail/sender.hpp"
#include "adapters/mqtt/detail/tcp_nodelay.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::adapters::mqtt {

struct Client::Impl : std::enable_shared_from_this<Client::Impl> {
public:
    Impl(boost::asio::any_io_executor loop, ClientOptions options);
    ~Impl();
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    /// Binds the loop's work to this object's life and starts the sender's thread; once, right
    /// after make_shared.
    void start_parts();

    detail::Connection& connection() { return connection_; }
    const detail::Connection& connection() const { return connection_; }
    detail::Sender& sender() { return sender_; }
    const detail::Sender& sender() const { return sender_; }

    /// Client::stop.
    void stop(std::chrono::milliseconds flush_timeout);

private:
    // client_stop.cpp: stop()'s steps
    /// On the loop, if it still runs: no more connects, no timers.
    void stop_loop_work();
    /// No link to flush to: ends the sender, counting what it leaves.
    void stop_disconnected();
    /// Waits for the last of our own publications (`offline` or the will) until `deadline`.
    void wait_for_last(const ::mqtt::delivery_token_ptr& last, core::MonoTime deadline) const;

    const ClientOptions options_;
    detail::LoopPost loop_;
    detail::NagleSwitch nagle_;
    /// Shared by the Sender (publish) and the Connection (the rest); reset in ~Impl.
    std::unique_ptr<::mqtt::async_client> paho_;
    detail::Sender sender_;
    detail::Connection connection_;
};

}  // namespace eip2mqtt::adapters::mqtt
