#pragma once
/// Paho's connect options from ours: MQTT version, clean start and session expiry, keep-alive,
/// credentials, the `offline` will, TLS. Built once per client; Paho copies them on connect.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mqtt/connect_options.h>

#include <chrono>
#include <optional>

#include "adapters/mqtt/detail/broker_url.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

/// Sets `co` (default-constructed) in place: Paho C++ 1.2's connect_options keeps pointers
/// into itself for the C library, and a copied or moved one lost the session expiry and the
/// will (the persistent-session tests failed). TLS is on when the URL's scheme asks for it or
/// `options.tls` is given (Paho then decides by the scheme: a tls block with tcp:// is
/// ignored, which the caller should say).
void configure_connect_options(::mqtt::connect_options& co, const ClientOptions& options,
                               const std::optional<BrokerEndpoint>& endpoint,
                               std::chrono::seconds connect_timeout);

}  // namespace eip2mqtt::adapters::mqtt::detail
