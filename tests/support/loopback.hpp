#pragma once
/// The IPv4 loopback address with a port, as the socket calls of the test tools take it.

#include <arpa/inet.h>
#include <netinet/in.h>

#include <cstdint>

namespace eip2mqtt::test {

inline sockaddr_in loopback(std::uint16_t port) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return address;
}

}  // namespace eip2mqtt::test
