#pragma once
/// The load a configuration's produced exchanges put on the network (`eip2mqtt check`): each
/// datagram counted as the bytes it takes on an Ethernet link, at the rate its period sets, and
/// the phase the gateway's scheduler gives its first send.

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::plan {

/// What a datagram takes on an Ethernet link besides its data bytes: preamble and start
/// delimiter 8, Ethernet header 14, IPv4 header 20 (no options), UDP header 8, EIP header 32,
/// frame check sequence 4, inter-frame gap 12. No padding: the shortest datagram (1 data byte)
/// makes a 79-byte frame, over Ethernet's 64; no fragments: 1400 data bytes make a 1460-byte IP
/// packet, under the 1500-byte MTU. No VLAN tag.
inline constexpr std::size_t ethernet_preamble_bytes = 8;
inline constexpr std::size_t ethernet_header_bytes = 14;
inline constexpr std::size_t ethernet_fcs_bytes = 4;
inline constexpr std::size_t ethernet_gap_bytes = 12;
inline constexpr std::size_t ipv4_header_bytes = 20;
inline constexpr std::size_t udp_header_bytes = 8;
inline constexpr std::size_t wire_overhead_bytes =
    ethernet_preamble_bytes + ethernet_header_bytes + ipv4_header_bytes + udp_header_bytes +
    wire::header_size + ethernet_fcs_bytes + ethernet_gap_bytes;

/// Bytes one datagram of `data_length` data bytes takes on the link.
constexpr std::size_t wire_bytes(std::size_t data_length) {
    return wire_overhead_bytes + data_length;
}

/// Bytes a datagram of `datagram_bytes` (its UDP payload: header and data) takes on the link.
constexpr std::size_t wire_bytes_of_datagram(std::size_t datagram_bytes) {
    return wire_overhead_bytes - wire::header_size + datagram_bytes;
}

/// A flow of datagrams on the link.
struct Rate {
    double datagrams_per_s = 0;
    double bits_per_s = 0;  ///< on the wire, overhead included
};

struct ExchangeLoad {
    std::string name;
    std::string destination;  ///< as configured
    double datagrams_per_s = 0;
    double bits_per_s = 0;  ///< on the wire, overhead included
    /// When its first datagram leaves after the gateway starts: the `index`-th of `count`
    /// produced exchanges starts period x index / count in (exchange::ProductionSchedule).
    std::chrono::nanoseconds phase{0};
};

struct DestinationLoad {
    std::string destination;  ///< as configured: `host` and `host:18246` are told apart
    std::size_t exchanges = 0;
    double datagrams_per_s = 0;
    double bits_per_s = 0;
};

struct NetworkLoad {
    std::vector<ExchangeLoad> exchanges;        ///< the produced ones, in configuration order
    std::vector<DestinationLoad> destinations;  ///< in order of first appearance
    double datagrams_per_s = 0;
    double bits_per_s = 0;

    /// The share of a link of `link_mbps` Mbit/s the datagrams take (1 = all of it).
    double link_share(double link_mbps) const { return bits_per_s / (link_mbps * 1e6); }
};

/// The load of the produced exchanges among `plans` (consumed ones are ignored).
NetworkLoad network_load(const std::vector<ExchangePlan>& plans);

/// What every exchange of `plans`, consumed and produced alike, puts on the link when each is
/// sent at its period: the traffic a capture of the configuration's network should see.
Rate configured_rate(const std::vector<ExchangePlan>& plans);

}  // namespace eip2mqtt::core::plan
