#include "eip2mqtt/adapters/capture/frame.hpp"

#include <optional>

namespace eip2mqtt::adapters::capture {
namespace {

constexpr std::uint16_t ethertype_ipv4 = 0x0800;
constexpr int family_inet = 2;  // AF_INET on every system that writes DLT_NULL/DLT_LOOP
constexpr std::uint8_t protocol_udp = 17;
constexpr std::size_t ipv4_min_header = 20;
constexpr std::size_t udp_header = 8;

std::uint16_t be16(std::span<const std::byte> bytes, std::size_t at) {
    return static_cast<std::uint16_t>(std::to_integer<unsigned>(bytes[at]) << 8 |
                                      std::to_integer<unsigned>(bytes[at + 1]));
}

std::uint32_t be32(std::span<const std::byte> bytes, std::size_t at) {
    return static_cast<std::uint32_t>(be16(bytes, at)) << 16 | be16(bytes, at + 2);
}

/// The IPv4 packet inside an Ethernet frame, past its VLAN tags; nullopt for another protocol.
std::optional<std::span<const std::byte>> ethernet_payload(std::span<const std::byte> frame) {
    std::size_t type_at = 12;
    for (int tags = 0; tags <= 2; ++tags) {
        if (frame.size() < type_at + 2) return std::nullopt;
        const auto type = be16(frame, type_at);
        if (type == ethertype_ipv4) return frame.subspan(type_at + 2);
        if (type != 0x8100 && type != 0x88A8 && type != 0x9100) return std::nullopt;
        type_at += 4;  // 802.1Q / 802.1ad tag: TPID then TCI
    }
    return std::nullopt;
}

/// The IPv4 packet of a frame of `link_type`; a skip reason otherwise.
core::Result<std::span<const std::byte>, FrameSkip> ip_packet(int link_type,
                                                              std::span<const std::byte> frame) {
    const auto after = [&](std::size_t header,
                           bool is_ipv4) -> core::Result<std::span<const std::byte>, FrameSkip> {
        if (frame.size() < header) return core::fail(FrameSkip::malformed);
        if (!is_ipv4) return core::fail(FrameSkip::not_ipv4);
        return frame.subspan(header);
    };
    switch (link_type) {
        case link::ethernet: {
            const auto packet = ethernet_payload(frame);
            if (!packet) return core::fail(FrameSkip::not_ipv4);
            return *packet;
        }
        case link::linux_sll:  // pkttype, hatype, halen, address[8], protocol
            return after(16, frame.size() >= 16 && be16(frame, 14) == ethertype_ipv4);
        case link::linux_sll2:  // protocol, reserved, ifindex, hatype, pkttype, halen, address[8]
            return after(20, frame.size() >= 20 && be16(frame, 0) == ethertype_ipv4);
        case link::null:
            // Host byte order of the machine that captured: either way round.
            return after(4, frame.size() >= 4 && (std::to_integer<int>(frame[0]) == family_inet ||
                                                  std::to_integer<int>(frame[3]) == family_inet));
        case link::loop:
            return after(4, frame.size() >= 4 && be32(frame, 0) == family_inet);
        case link::raw:
        case link::ipv4:
            return frame;
        default:
            return core::fail(FrameSkip::unknown_link);
    }
}

}  // namespace

core::Result<UdpFrame, FrameSkip> decode_frame(int link_type, std::span<const std::byte> frame) {
    auto ip = ip_packet(link_type, frame);
    if (!ip) return core::fail(ip.error());
    auto packet = ip.value();
    if (packet.empty() || std::to_integer<unsigned>(packet[0]) >> 4 != 4) {
        return core::fail(FrameSkip::not_ipv4);
    }
    const std::size_t header = (std::to_integer<std::size_t>(packet[0]) & 0x0F) * 4;
    if (header < ipv4_min_header || packet.size() < header) return core::fail(FrameSkip::malformed);
    const std::size_t total = be16(packet, 2);
    if (total < header) return core::fail(FrameSkip::malformed);
    // Ethernet pads short frames: the IP total length says where the packet ends.
    if (packet.size() > total) packet = packet.first(total);
    if (std::to_integer<unsigned>(packet[9]) != protocol_udp) return core::fail(FrameSkip::not_udp);
    if ((be16(packet, 6) & 0x3FFF) != 0) return core::fail(FrameSkip::fragment);  // MF or offset

    const auto udp = packet.subspan(header);
    if (udp.size() < udp_header) return core::fail(FrameSkip::malformed);
    const std::size_t udp_length = be16(udp, 4);
    if (udp_length < udp_header || udp_length > total - header) {
        return core::fail(FrameSkip::malformed);
    }
    UdpFrame result;
    result.source = be32(packet, 12);
    result.destination = be32(packet, 16);
    result.source_port = be16(udp, 0);
    result.destination_port = be16(udp, 2);
    const std::size_t announced = udp_length - udp_header;
    const std::size_t captured = udp.size() - udp_header;
    result.truncated = captured < announced;
    result.payload = udp.subspan(udp_header, result.truncated ? captured : announced);
    return result;
}

}  // namespace eip2mqtt::adapters::capture
