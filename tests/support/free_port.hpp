#pragma once
/// Free loopback ports for hermetic tests: bind port 0, read the port back, close.

#include <cstdint>

namespace eip2mqtt::test {

std::uint16_t free_tcp_port();
std::uint16_t free_udp_port();

}  // namespace eip2mqtt::test
