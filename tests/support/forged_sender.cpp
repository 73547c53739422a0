#include "tests/support/forged_sender.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/ip.h>
#include <netinet/udp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>

namespace eip2mqtt::test {

ForgedSender::ForgedSender(int raw_fd) : fd_(raw_fd) {}

ForgedSender::~ForgedSender() {
    if (fd_ >= 0) ::close(fd_);
}

bool ForgedSender::send(const std::string& source, std::uint16_t source_port,
                        const std::string& destination, std::uint16_t destination_port,
                        const std::vector<std::byte>& payload) {
    std::vector<std::byte> packet(sizeof(iphdr) + sizeof(udphdr) + payload.size());
    iphdr ip{};
    ip.version = 4;
    ip.ihl = 5;
    ip.ttl = 64;
    ip.protocol = IPPROTO_UDP;
    ip.tot_len = htons(static_cast<std::uint16_t>(packet.size()));  // the kernel checks it
    if (::inet_pton(AF_INET, source.c_str(), &ip.saddr) != 1 ||
        ::inet_pton(AF_INET, destination.c_str(), &ip.daddr) != 1) {
        return false;
    }
    // The kernel fills in the IP header's checksum (raw(7)); a UDP checksum of 0 means none.
    udphdr udp{};
    udp.source = htons(source_port);
    udp.dest = htons(destination_port);
    udp.len = htons(static_cast<std::uint16_t>(sizeof(udphdr) + payload.size()));
    std::memcpy(packet.data(), &ip, sizeof ip);
    std::memcpy(packet.data() + sizeof ip, &udp, sizeof udp);
    std::memcpy(packet.data() + sizeof ip + sizeof udp, payload.data(), payload.size());
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = ip.daddr;
    return ::sendto(fd_, packet.data(), packet.size(), 0, reinterpret_cast<const sockaddr*>(&to),
                    sizeof to) == static_cast<ssize_t>(packet.size());
}

}  // namespace eip2mqtt::test
