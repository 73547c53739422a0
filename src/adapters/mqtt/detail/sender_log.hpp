#pragma once
/// What the Sender says of publications that failed: one line per event, throttled per kind
/// (core::ThrottledLog), with the count since the last line. Only failures come here: a
/// publication that goes well never touches it.
///
/// Threading: any thread (the sender's, Paho's); the throttles are kept under a mutex of its own,
/// never held with the Sender's.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mutex>
#include <string>

#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class SenderLog {
public:
    /// `log_name` (ClientOptions::log_name) and `clock` outlive it.
    SenderLog(const std::string& log_name, const core::Clock& clock)
        : log_name_(log_name), clock_(clock) {}

    /// A publication dropped before it was sent: a broker would refuse it (`problem`).
    void refused(const std::string& topic, const std::string& problem);
    /// A publication Paho or the broker failed, for `reason`.
    void publish_failure(const std::string& topic, const std::string& reason);
    /// A suspect that failed again when sent alone: dropped (every one is logged).
    void dropped_suspect(const std::string& topic);

private:
    const std::string& log_name_;
    const core::Clock& clock_;
    std::mutex mutex_;
    core::ThrottledLog refused_log_;
    core::ThrottledLog publish_failure_log_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
