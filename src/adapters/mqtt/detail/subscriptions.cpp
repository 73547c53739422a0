#include "adapters/mqtt/detail/subscriptions.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iterator>
#include <set>
#include <utility>

#include "adapters/mqtt/detail/paho_tokens.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

void Subscriptions::Listener::on_failure(const paho::token& tok) {
    subscriptions_.loop_.post([&s = subscriptions_, reason = describe_failure(tok)] {
        spdlog::warn("{} subscribe failed on {}: {}", s.options_.log_name, s.brokers_.url(),
                     reason);
    });
}

void Subscriptions::set(std::vector<std::string> filters, bool connected) {
    std::set<std::string> old(filters_.begin(), filters_.end());
    std::set<std::string> now(filters.begin(), filters.end());
    std::vector<std::string> added;
    std::vector<std::string> removed;
    std::set_difference(now.begin(), now.end(), old.begin(), old.end(), std::back_inserter(added));
    std::set_difference(old.begin(), old.end(), now.begin(), now.end(),
                        std::back_inserter(removed));
    filters_ = std::move(filters);
    if (!connected) {
        return;  // subscribed on the next connect
    }
    subscribe(added);
    unsubscribe(removed);
}

void Subscriptions::subscribe(const std::vector<std::string>& filters) {
    if (filters.empty()) {
        return;
    }
    const bool v5 = options_.version == 5;
    // no_local: never hear our own publications (unless asked: hear_own). Retain-as-published:
    // a write published with retain keeps its flag when forwarded live, as it has when a new
    // subscription fetches it later, so the gateway can refuse retained writes either way.
    const paho::subscribe_options opt(v5 && !options_.hear_own, v5 && options_.retain_as_published);
    try {
        // One SUBSCRIBE per filter: Paho C++ 1.2's many-topic overload crashes inside
        // MQTTAsync_subscribeMany when given subscribe options, and its one-topic overload is
        // the only one that passes them on.
        for (const auto& filter : filters) {
            paho_.subscribe(filter, options_.subscription_qos, nullptr, listener_, opt);
        }
    } catch (const paho::exception& e) {
        spdlog::warn("{} subscribe failed on {}: {}", options_.log_name, brokers_.url(), e.what());
    }
}

void Subscriptions::unsubscribe(const std::vector<std::string>& filters) {
    if (filters.empty()) {
        return;
    }
    try {
        paho_.unsubscribe(paho::string_collection::create(filters));
    } catch (const paho::exception& e) {
        spdlog::warn("{} unsubscribe failed on {}: {}", options_.log_name, brokers_.url(),
                     e.what());
    }
}

}  // namespace eip2mqtt::adapters::mqtt::detail
