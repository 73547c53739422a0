#pragma once
/// Figures of the gateway's Prometheus page, for tests that wait on what the gateway counted.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace eip2mqtt::test {

/// The figure `name` (a sample without labels) of /metrics on 127.0.0.1:`port`; nullopt when
/// the page does not hold it or nothing answered.
std::optional<double> prometheus_figure(std::uint16_t port, const std::string& name);

/// Polls /metrics (bounded by `timeout`) until `name` satisfies `pred`; false on the timeout.
bool wait_prometheus_figure(std::uint16_t port, const std::string& name,
                            const std::function<bool(double)>& pred,
                            std::chrono::seconds timeout = std::chrono::seconds(20));

}  // namespace eip2mqtt::test
