#pragma once
/// Sets TCP_NODELAY on this process's TCP connections to the broker.
///
/// Why: Debian 12's Paho MQTT C (1.3.12) never sets TCP_NODELAY, so Nagle's algorithm holds a
/// small QoS 0 publication back until the broker's delayed ACK of the previous one (p99 about
/// 12 ms on loopback). Paho does not expose its socket, so we find it: every fd in
/// /proc/self/fd that is a SOCK_STREAM socket whose peer is one of the broker's resolved
/// addresses and port. Sockets already set are left alone. Another client of the same broker in
/// this process (a test's recorder) gets the option too, which does it no harm.
///
/// Module-private (src/adapters/mqtt/detail); called on the loop after each connect.

#include <cstddef>
#include <cstdint>
#include <string>

namespace eip2mqtt::adapters::mqtt::detail {

/// Resolves `host` (blocking getaddrinfo; numeric hosts resolve instantly) and sets TCP_NODELAY
/// on every matching socket that did not have it. Returns how many sockets were changed.
std::size_t set_tcp_nodelay_to(const std::string& host, std::uint16_t port);

}  // namespace eip2mqtt::adapters::mqtt::detail
