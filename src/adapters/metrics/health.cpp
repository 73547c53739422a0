#include "eip2mqtt/adapters/metrics/health.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace eip2mqtt::adapters::metrics {
namespace {

/// Stale exchanges named in a reason; the rest are counted, so a plant-wide outage stays a line.
constexpr std::size_t max_named = 10;

std::string stale_exchanges(const MetricsSnapshot& snapshot) {
    std::vector<std::string> stale;
    for (const auto& exchange : snapshot.exchanges) {
        if (exchange.state == "stale") stale.push_back(exchange.name);
    }
    if (stale.empty()) return {};
    std::string text = stale.size() == 1 ? "exchange " : "exchanges ";
    const auto named = std::min(stale.size(), max_named);
    for (std::size_t i = 0; i < named; ++i) text += (i > 0 ? ", " : "") + stale[i];
    if (stale.size() > named) text += fmt::format(" and {} more", stale.size() - named);
    return text + (stale.size() == 1 ? " is stale" : " are stale");
}

/// With several connections, each one down is named: one broker's outage is not the others'.
std::string mqtt_down(const GatewayMetrics& gateway) {
    if (gateway.connections.empty()) return gateway.mqtt_connected ? "" : "MQTT is not connected";
    std::string down;
    for (const auto& connection : gateway.connections) {
        if (!connection.connected) down += (down.empty() ? "" : ", ") + connection.name;
    }
    if (down.empty()) return {};
    return "MQTT connection " + down + (down.find(',') == std::string::npos ? " is" : " are") +
           " not connected";
}

std::string not_ready_reason(const MetricsSnapshot& snapshot) {
    std::string reason = mqtt_down(snapshot.gateway);
    if (auto stale = stale_exchanges(snapshot); !stale.empty()) {
        reason += (reason.empty() ? "" : "; ") + stale;
    }
    return reason;
}

double seconds(HealthState::Clock::duration duration) {
    return std::chrono::duration<double>(duration).count();
}

}  // namespace

HealthState::HealthState(Clock::duration liveness_timeout, const core::Clock& clock)
    : liveness_timeout_(liveness_timeout), clock_(clock) {}

void HealthState::update(const MetricsSnapshot& snapshot, Clock::time_point now) {
    auto reason = not_ready_reason(snapshot);
    std::lock_guard lock(mutex_);
    last_update_ = now;
    not_ready_.swap(reason);
}

HealthAnswer HealthState::liveness(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    return liveness_locked(now);
}

HealthAnswer HealthState::readiness(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    auto live = liveness_locked(now);
    if (live.status != 200) return live;
    if (!not_ready_.empty()) return {503, "not ready: " + not_ready_ + "\n"};
    return {200, "ready\n"};
}

HealthAnswer HealthState::liveness_locked(Clock::time_point now) const {
    if (!last_update_) return {503, "starting: the gateway's loop has not reported yet\n"};
    const auto silent = now - *last_update_;
    if (silent > liveness_timeout_) {
        return {503,
                fmt::format("the gateway's loop has not reported for {:.1f} s (limit {:.1f} s)\n",
                            seconds(silent), seconds(liveness_timeout_))};
    }
    return {200, "ok\n"};
}

}  // namespace eip2mqtt::adapters::metrics
