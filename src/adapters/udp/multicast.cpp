#include "eip2mqtt/adapters/udp/multicast.hpp"

#include <arpa/inet.h>
#include <net/if.h>
#include <netinet/in.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <string_view>
#include <system_error>

#include "eip2mqtt/adapters/udp/endpoint.hpp"

namespace eip2mqtt::adapters::udp {

namespace {

ip_mreqn membership_request(const MulticastMembership& membership) {
    const auto group = parse_ipv4(membership.group);
    if (!group) {
        throw std::system_error(
            std::make_error_code(std::errc::invalid_argument),
            "multicast group '" + membership.group + "' is not an IPv4 address");
    }
    ip_mreqn request{};
    request.imr_multiaddr.s_addr = htonl(*group);
    if (!membership.interface.empty()) {
        if (auto address = parse_ipv4(membership.interface)) {
            request.imr_address.s_addr = htonl(*address);
        } else {
            const unsigned index = if_nametoindex(membership.interface.c_str());
            if (index == 0) {
                throw std::system_error(errno, std::generic_category(),
                                        "multicast interface '" + membership.interface + "'");
            }
            request.imr_ifindex = static_cast<int>(index);
        }
    }
    return request;
}

std::string_view interface_name(const MulticastMembership& membership) {
    if (membership.interface.empty()) return "the default interface";
    return membership.interface;
}

}  // namespace

void join_group(int fd, const MulticastMembership& membership) {
    const auto request = membership_request(membership);
    if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &request, sizeof request) != 0) {
        throw std::system_error(errno, std::generic_category(),
                                "cannot join multicast group " + membership.group);
    }
    spdlog::info("joined multicast group {} on {}", membership.group, interface_name(membership));
}

void leave_group(int fd, const MulticastMembership& membership) {
    try {
        const auto request = membership_request(membership);
        if (setsockopt(fd, IPPROTO_IP, IP_DROP_MEMBERSHIP, &request, sizeof request) != 0) {
            throw std::system_error(errno, std::generic_category(), "setsockopt");
        }
        spdlog::info("left multicast group {} on {}", membership.group, interface_name(membership));
    } catch (const std::system_error& e) {
        spdlog::warn("cannot leave multicast group {} on {}: {}", membership.group,
                     interface_name(membership), e.what());
    }
}

GroupMemberships::GroupMemberships(const std::vector<MulticastMembership>& groups) {
    if (groups.empty()) return;
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "UDP socket");
    // Datagrams of other groups joined on this host must not queue here unread either.
    const int off = 0;
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_ALL, &off, sizeof off);
    try {
        for (const auto& membership : groups) join_group(fd_, membership);
    } catch (...) {
        ::close(fd_);
        throw;
    }
}

GroupMemberships::~GroupMemberships() {
    if (fd_ >= 0) ::close(fd_);
}

}  // namespace eip2mqtt::adapters::udp
