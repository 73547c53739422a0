#include "tests/support/udp_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>
#include <utility>

namespace eip2mqtt::test {

UdpClient::UdpClient(std::uint16_t port, std::uint32_t bind_address) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd_ < 0) throw std::runtime_error("socket failed");
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(bind_address);
    address.sin_port = htons(port);
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
        throw std::runtime_error("bind failed");
    }
    socklen_t length = sizeof address;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
}

UdpClient::~UdpClient() { ::close(fd_); }

void UdpClient::send_to(std::uint16_t port, const std::vector<std::byte>& datagram) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    const auto sent = ::sendto(fd_, datagram.data(), datagram.size(), 0,
                               reinterpret_cast<sockaddr*>(&address), sizeof address);
    if (sent != static_cast<ssize_t>(datagram.size())) throw std::runtime_error("sendto failed");
}

std::optional<std::vector<std::byte>> UdpClient::receive(std::chrono::milliseconds timeout) {
    auto received = receive_from(timeout);
    if (!received) return std::nullopt;
    return std::move(received->bytes);
}

std::optional<std::vector<std::byte>> UdpClient::latest(std::chrono::milliseconds timeout) {
    std::optional<std::vector<std::byte>> last;
    while (auto bytes = receive(std::chrono::milliseconds{0})) last = std::move(bytes);
    return last ? last : receive(timeout);
}

std::optional<UdpDatagram> UdpClient::receive_from(std::chrono::milliseconds timeout) {
    pollfd pfd{fd_, POLLIN, 0};
    if (::poll(&pfd, 1, static_cast<int>(timeout.count())) <= 0) return std::nullopt;
    UdpDatagram received;
    received.bytes.resize(65536);
    sockaddr_in from{};
    socklen_t length = sizeof from;
    const auto n = ::recvfrom(fd_, received.bytes.data(), received.bytes.size(), 0,
                              reinterpret_cast<sockaddr*>(&from), &length);
    if (n < 0) return std::nullopt;
    received.bytes.resize(static_cast<std::size_t>(n));
    received.from_port = ntohs(from.sin_port);
    return received;
}

}  // namespace eip2mqtt::test
