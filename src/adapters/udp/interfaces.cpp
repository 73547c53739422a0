#include "eip2mqtt/adapters/udp/interfaces.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <algorithm>

namespace eip2mqtt::adapters::udp {

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

}  // namespace eip2mqtt::adapters::udp
