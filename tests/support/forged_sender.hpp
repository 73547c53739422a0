#pragma once
/// Sends UDP datagrams whose IPv4 source address is forged: a raw socket (IPPROTO_RAW, so the
/// test writes the IP header itself, IP_HDRINCL) made by the test inside one of its network
/// namespaces, or on loopback. What a hostile node on the segment can do to a gateway.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace eip2mqtt::test {

class ForgedSender {
public:
    /// Takes `raw_fd`, a socket(AF_INET, SOCK_RAW, IPPROTO_RAW); closes it at the end.
    explicit ForgedSender(int raw_fd);
    ~ForgedSender();
    ForgedSender(const ForgedSender&) = delete;
    ForgedSender& operator=(const ForgedSender&) = delete;

    /// One datagram from `source`:`source_port` (dotted IPv4, any address at all) to
    /// `destination`:`destination_port`; false when the kernel refused it.
    bool send(const std::string& source, std::uint16_t source_port, const std::string& destination,
              std::uint16_t destination_port, const std::vector<std::byte>& payload);

private:
    int fd_;
};

}  // namespace eip2mqtt::test
