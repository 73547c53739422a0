#pragma once
/// What the host's network interfaces say about addresses, for telling a subnet-directed
/// broadcast from a unicast datagram (`sniff --yaml`, the command responder's Retrieve
/// Configuration) and for the command responder's default requesters.

#include <cstdint>
#include <vector>

#include "eip2mqtt/core/net/subnet.hpp"

namespace eip2mqtt::adapters::udp {

/// The IPv4 broadcast address of every interface that has one (getifaddrs), host byte order;
/// empty when the interfaces cannot be read.
std::vector<std::uint32_t> local_broadcast_addresses();

/// The IPv4 subnet of each interface address `bind` (host byte order) names: the interface
/// holding that address, or, for 0.0.0.0, every interface that is up. Empty when none does or
/// the interfaces cannot be read.
std::vector<core::net::Subnet> local_subnets(std::uint32_t bind);

}  // namespace eip2mqtt::adapters::udp
