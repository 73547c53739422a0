#pragma once
/// Free loopback ports for hermetic tests: bind port 0, read the port back, close.

#include <cstdint>

namespace eip2mqtt::test {

std::uint16_t free_tcp_port();
std::uint16_t free_udp_port();

/// Whether something accepts TCP connections on 127.0.0.1:`port` now.
bool accepts_connections(std::uint16_t port);

}  // namespace eip2mqtt::test
