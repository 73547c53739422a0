#pragma once
/// What /healthz and /readyz answer on the metrics listener (docs/operations.md, "Health"), worked
/// out from the snapshots the gateway's loop hands the endpoint about once a second: a loop that
/// stops handing them over is not live; the gateway is ready while MQTT is connected and no
/// consumed exchange is stale.

#include <chrono>
#include <mutex>
#include <optional>
#include <string>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/metrics/prometheus_endpoint.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::adapters::metrics {

/// One answer: 200 or 503, and a one-line body saying why.
struct HealthAnswer {
    int status = 503;
    std::string body;
};

/// Thread-safe: update() is called from the loop, the answers from the HTTP server's threads.
class HealthState {
public:
    using Clock = std::chrono::steady_clock;

    /// A loop that has not called update() for longer than `liveness_timeout` is not live.
    /// `clock` (outliving it) is the time its callers read for the answers and the updates.
    explicit HealthState(Clock::duration liveness_timeout,
                         const core::Clock& clock = adapters::clock::system_clock());

    const core::Clock& clock() const { return clock_; }

    void update(const MetricsSnapshot& snapshot, Clock::time_point now);

    /// /healthz: 200 "ok" while updates come; 503 before the first and once they stop.
    HealthAnswer liveness(Clock::time_point now) const;
    /// /readyz: 200 "ready" while live, MQTT connected and no exchange stale; else 503
    /// "not ready: " and every reason (`MQTT is not connected`, `exchange pump is stale`).
    HealthAnswer readiness(Clock::time_point now) const;

private:
    HealthAnswer liveness_locked(Clock::time_point now) const;

    const Clock::duration liveness_timeout_;
    const core::Clock& clock_;
    mutable std::mutex mutex_;
    std::optional<Clock::time_point> last_update_;
    std::string not_ready_;  ///< empty when ready
};

}  // namespace eip2mqtt::adapters::metrics
