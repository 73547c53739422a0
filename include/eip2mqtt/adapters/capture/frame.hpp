#pragma once
/// Decodes one captured link-layer frame down to the payload of its IPv4 UDP datagram, for the
/// passive capture of `sniff`. Pure: no libpcap call, so that it is fuzzed and unit-tested alone.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::capture {

/// The link types the capture decodes (libpcap's DLT_ values on Linux, pcap-linktype(7)).
namespace link {
inline constexpr int null = 0;          ///< BSD loopback: the address family in host order
inline constexpr int ethernet = 1;      ///< Ethernet II, with up to two VLAN tags
inline constexpr int raw = 12;          ///< raw IP
inline constexpr int loop = 108;        ///< OpenBSD loopback: the family in network order
inline constexpr int linux_sll = 113;   ///< Linux cooked capture v1 (the "any" device)
inline constexpr int ipv4 = 228;        ///< raw IPv4
inline constexpr int linux_sll2 = 276;  ///< Linux cooked capture v2
}  // namespace link

/// One UDP datagram as captured.
struct UdpFrame {
    std::uint32_t source = 0;  ///< IPv4, host byte order
    std::uint16_t source_port = 0;
    std::uint32_t destination = 0;  ///< IPv4, host byte order: unicast, broadcast or group
    std::uint16_t destination_port = 0;
    std::span<const std::byte> payload;  ///< views the frame; valid as long as it
    /// The capture holds less than the UDP header announces (the snapshot length cut it): the
    /// payload is what was captured.
    bool truncated = false;
};

/// Why a frame carries no UDP datagram to decode.
enum class FrameSkip {
    unknown_link,  ///< a link type not listed in `link`
    not_ipv4,      ///< another protocol (IPv6, ARP...): EIP runs on IPv4
    not_udp,
    fragment,   ///< an IP fragment: only whole datagrams are decoded
    malformed,  ///< headers shorter than they must be or lengths that contradict each other
};

inline constexpr auto frame_skip_names =
    core::enum_names<FrameSkip>("unknown_link", "not_ipv4", "not_udp", "fragment", "malformed");

constexpr std::string_view to_string(FrameSkip skip) { return frame_skip_names.name_of(skip); }

/// Decodes `frame`, captured on a link of `link_type`.
core::Result<UdpFrame, FrameSkip> decode_frame(int link_type, std::span<const std::byte> frame);

}  // namespace eip2mqtt::adapters::capture
