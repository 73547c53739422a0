#pragma once
/// The brokers of ClientOptions::urls, tried in turn, and which of them is current: the one
/// being tried or connected to. The next after a failed attempt or a lost connection, the first
/// after the last.
///
/// Threading: move_to_next() on the loop; the rest from any thread too (stats): the list never
/// changes and the index only names one of it.
///
/// Module-private (src/adapters/mqtt/detail).

#include <atomic>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "adapters/mqtt/detail/broker_url.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class BrokerList {
public:
    /// `urls` is not empty and outlives it.
    explicit BrokerList(const std::vector<std::string>& urls);

    /// The URL of the current broker.
    const std::string& url() const { return urls_[current_]; }
    /// What the current broker's URL names (nullopt: not a URL parse_broker_url knows).
    const std::optional<BrokerEndpoint>& endpoint() const { return endpoints_[current_]; }
    /// What the first URL names: every broker of a list has the same scheme.
    const std::optional<BrokerEndpoint>& first_endpoint() const { return endpoints_.front(); }
    /// After a failed attempt or a lost connection: the next attempt goes to the next broker.
    void move_to_next() { current_ = next_broker(current_, urls_.size()); }

private:
    const std::vector<std::string>& urls_;
    const std::vector<std::optional<BrokerEndpoint>> endpoints_;
    /// Index in urls_ of the current broker; written on the loop.
    std::atomic<std::size_t> current_{0};
};

}  // namespace eip2mqtt::adapters::mqtt::detail
