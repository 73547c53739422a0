#include "eip2mqtt/adapters/udp/interfaces.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <algorithm>

namespace eip2mqtt::adapters::udp {
namespace {

std::uint32_t ipv4_of(const sockaddr* address) {
    sockaddr_in in{};
    std::copy_n(reinterpret_cast<const unsigned char*>(address), sizeof in,
                reinterpret_cast<unsigned char*>(&in));
    return ntohl(in.sin_addr.s_addr);
}

std::uint8_t prefix_of(std::uint32_t netmask) {
    return static_cast<std::uint8_t>(__builtin_popcount(netmask));
}

}  // namespace

std::vector<std::uint32_t> local_broadcast_addresses() {
    std::vector<std::uint32_t> addresses;
    ifaddrs* list = nullptr;
    if (::getifaddrs(&list) != 0) return addresses;
    for (const ifaddrs* entry = list; entry != nullptr; entry = entry->ifa_next) {
        if ((entry->ifa_flags & IFF_BROADCAST) == 0 || entry->ifa_broadaddr == nullptr ||
            entry->ifa_broadaddr->sa_family != AF_INET) {
            continue;
        }
        sockaddr_in broadcast{};
        std::copy_n(reinterpret_cast<const unsigned char*>(entry->ifa_broadaddr), sizeof broadcast,
                    reinterpret_cast<unsigned char*>(&broadcast));
        const auto address = ntohl(broadcast.sin_addr.s_addr);
        if (std::find(addresses.begin(), addresses.end(), address) == addresses.end()) {
            addresses.push_back(address);
        }
    }
    ::freeifaddrs(list);
    return addresses;
}

std::vector<core::net::Subnet> local_subnets(std::uint32_t bind) {
    std::vector<core::net::Subnet> subnets;
    ifaddrs* list = nullptr;
    if (::getifaddrs(&list) != 0) return subnets;
    for (const ifaddrs* entry = list; entry != nullptr; entry = entry->ifa_next) {
        if ((entry->ifa_flags & IFF_UP) == 0 || entry->ifa_addr == nullptr ||
            entry->ifa_netmask == nullptr || entry->ifa_addr->sa_family != AF_INET) {
            continue;
        }
        const auto address = ipv4_of(entry->ifa_addr);
        if (bind != 0 && address != bind) continue;
        const auto mask = ipv4_of(entry->ifa_netmask);
        const core::net::Subnet subnet{address & mask, prefix_of(mask)};
        if (std::find(subnets.begin(), subnets.end(), subnet) == subnets.end()) {
            subnets.push_back(subnet);
        }
    }
    ::freeifaddrs(list);
    return subnets;
}

}  // namespace eip2mqtt::adapters::udp
