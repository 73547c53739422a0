#pragma once
/// What the Connection says when a connection fails or goes: a failed attempt's reason made
/// into words an operator can act on (what the connect token knows, what to check over TLS, an
/// MQTT 5 refusal), the throttle of those lines, and the pattern of silent, short-lived losses
/// (connection_reasons.hpp) measured from the time the connection was made.
///
/// Threading: the loop's.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mqtt/async_client.h>

#include <cstdint>
#include <optional>
#include <string>

#include "adapters/mqtt/detail/broker_url.hpp"
#include "adapters/mqtt/detail/connection_reasons.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class ConnectDiagnosis {
public:
    /// `options` (its version, client id and clock) outlives it.
    explicit ConnectDiagnosis(const ClientOptions& options) : options_(options) {}

    /// A connection is up: its lifetime starts, and failed attempts are logged afresh.
    void on_connected();

    /// The reason to log for a failed attempt to `endpoint`: Paho's `reason` and, for Paho's
    /// generic failure, what `token` (the attempt's) carries and, over TLS, what to check; for
    /// MQTT 5, what the broker's refusal (`return_code`) means.
    std::string explain_connect_failure(std::string reason, int return_code,
                                        const ::mqtt::token_ptr& token,
                                        const std::optional<BrokerEndpoint>& endpoint) const;
    /// Counts a failed attempt; how many since the last line when one is to be logged now
    /// (core::ThrottledLog), else 0.
    std::uint64_t record_connect_failure();

    /// The cause to log for a lost connection: `cause`, unless the broker gave none (`silent`),
    /// then what the pattern of such losses suggests.
    std::string explain_loss(std::string cause, bool silent);

private:
    const ClientOptions& options_;
    core::ThrottledLog connect_failure_log_;
    core::MonoTime connected_at_{};
    SilentLossPattern silent_losses_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
