#pragma once
/// The client's topic filters (QoS 1): kept for every connect, subscribed anew after each, and
/// on a change while connected, what is new subscribed and what is gone unsubscribed.
///
/// Threading: the loop's; Paho's thread reports a failed SUBSCRIBE, posted to the loop.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mqtt/async_client.h>

#include <string>
#include <vector>

#include "adapters/mqtt/detail/broker_list.hpp"
#include "adapters/mqtt/detail/loop_post.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class Subscriptions {
public:
    /// `options`, `paho`, `loop` and `brokers` (for the log lines) outlive it.
    Subscriptions(const ClientOptions& options, ::mqtt::async_client& paho, const LoopPost& loop,
                  const BrokerList& brokers)
        : options_(options), paho_(paho), loop_(loop), brokers_(brokers) {}
    Subscriptions(const Subscriptions&) = delete;
    Subscriptions& operator=(const Subscriptions&) = delete;

    /// Keeps `filters` for every connect; when `connected`, subscribes what is new and
    /// unsubscribes what is gone now.
    void set(std::vector<std::string> filters, bool connected);
    /// Just connected: subscribes every filter.
    void renew() { subscribe(filters_); }

private:
    struct Listener final : ::mqtt::iaction_listener {
        explicit Listener(Subscriptions& subscriptions) : subscriptions_(subscriptions) {}
        void on_success(const ::mqtt::token&) override {}
        void on_failure(const ::mqtt::token& tok) override;
        Subscriptions& subscriptions_;
    };

    void subscribe(const std::vector<std::string>& filters);
    void unsubscribe(const std::vector<std::string>& filters);

    const ClientOptions& options_;
    ::mqtt::async_client& paho_;
    const LoopPost& loop_;
    const BrokerList& brokers_;
    std::vector<std::string> filters_;
    Listener listener_{*this};
};

}  // namespace eip2mqtt::adapters::mqtt::detail
