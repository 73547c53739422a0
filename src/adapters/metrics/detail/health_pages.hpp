#pragma once
/// /healthz and /readyz on the metrics listener: civetweb's begin_request callback answers them
/// before prometheus-cpp's handlers see the request. The callback is a plain function of the
/// connection, so it finds the HealthState of the listener a request came to by its port.

#include <CivetServer.h>

#include <memory>

#include "eip2mqtt/adapters/metrics/health.hpp"

namespace eip2mqtt::adapters::metrics::detail {

/// The callbacks to hand prometheus::Exposer; they live as long as the process.
const CivetCallbacks& health_callbacks();

/// Requests to `port` are answered from `state` until unregister_health(port). Thread-safe.
void register_health(int port, std::shared_ptr<const HealthState> state);
void unregister_health(int port);

}  // namespace eip2mqtt::adapters::metrics::detail
