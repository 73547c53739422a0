#pragma once
/// What the host's network interfaces say about addresses, for telling a subnet-directed
/// broadcast from a unicast datagram (`sniff --yaml`).

#include <cstdint>
#include <vector>

namespace eip2mqtt::adapters::udp {

/// The IPv4 broadcast address of every interface that has one (getifaddrs), host byte order;
/// empty when the interfaces cannot be read.
std::vector<std::uint32_t> local_broadcast_addresses();

}  // namespace eip2mqtt::adapters::udp
