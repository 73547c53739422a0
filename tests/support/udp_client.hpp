#pragma once
/// A plain UDP socket on loopback, for feeding datagrams to the gateway and capturing the
/// datagrams it produces.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace eip2mqtt::test {

/// A datagram with the port it came from (each process sends from a port of its own).
struct UdpDatagram {
    std::vector<std::byte> bytes;
    std::uint16_t from_port = 0;
};

class UdpClient {
public:
    /// Binds `address`:`port` (0: ephemeral); `address` is IPv4 in host order, on loopback
    /// (127.0.0.2 is another source on the same host).
    explicit UdpClient(std::uint16_t port = 0, std::uint32_t address = 0x7F000001);
    ~UdpClient();
    UdpClient(const UdpClient&) = delete;
    UdpClient& operator=(const UdpClient&) = delete;

    std::uint16_t port() const { return port_; }
    void send_to(std::uint16_t port, const std::vector<std::byte>& datagram);
    /// Next datagram received, or nullopt after `timeout`.
    std::optional<std::vector<std::byte>> receive(std::chrono::milliseconds timeout);
    /// The same, with the sender's port.
    std::optional<UdpDatagram> receive_from(std::chrono::milliseconds timeout);
    /// The newest of the datagrams queued so far or, when none is, the next one within
    /// `timeout`: a producer's current image whether or not its queue was drained before.
    std::optional<std::vector<std::byte>> latest(std::chrono::milliseconds timeout);

private:
    int fd_ = -1;
    std::uint16_t port_ = 0;
};

}  // namespace eip2mqtt::test
