// decode_frame: the UDP datagram inside each link type a capture delivers, and why a frame has
// none to decode (another protocol, a fragment, lengths that contradict each other).

#include "eip2mqtt/adapters/capture/frame.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "tests/support/enumerators.hpp"

namespace eip2mqtt::adapters::capture {
namespace EIP2MQTT_THIS_FILE {

using Bytes = std::vector<std::byte>;

void put16(Bytes& bytes, std::uint16_t value) {
    bytes.push_back(std::byte(value >> 8));
    bytes.push_back(std::byte(value & 0xFF));
}

/// An IPv4 header and UDP datagram from 10.0.0.9:5000 to 10.0.0.255:18246 with `payload`.
Bytes ip_udp(const Bytes& payload, std::uint16_t fragment_field = 0x4000) {
    Bytes ip;
    ip.push_back(std::byte{0x45});  // version 4, 20-byte header
    ip.push_back(std::byte{0});
    put16(ip, static_cast<std::uint16_t>(20 + 8 + payload.size()));
    put16(ip, 0x1234);          // identification
    put16(ip, fragment_field);  // DF by default
    ip.push_back(std::byte{64});
    ip.push_back(std::byte{17});  // UDP
    put16(ip, 0);                 // checksum, not checked
    for (int b : {10, 0, 0, 9, 10, 0, 0, 255}) ip.push_back(std::byte(b));
    put16(ip, 5000);
    put16(ip, 18246);
    put16(ip, static_cast<std::uint16_t>(8 + payload.size()));
    put16(ip, 0);
    ip.insert(ip.end(), payload.begin(), payload.end());
    return ip;
}

Bytes concat(Bytes head, const Bytes& tail) {
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
}

Bytes ethernet(const Bytes& packet, std::uint16_t type = 0x0800) {
    Bytes frame(12, std::byte{0xAA});  // destination and source MACs
    put16(frame, type);
    return concat(frame, packet);
}

const Bytes payload{std::byte{1}, std::byte{2}, std::byte{3}};

void expect_datagram(int link_type, const Bytes& frame) {
    const auto decoded = decode_frame(link_type, frame);
    ASSERT_TRUE(decoded) << to_string(decoded.error());
    EXPECT_EQ(decoded->source, 0x0A000009u);
    EXPECT_EQ(decoded->source_port, 5000);
    EXPECT_EQ(decoded->destination, 0x0A0000FFu);
    EXPECT_EQ(decoded->destination_port, 18246);
    EXPECT_EQ(Bytes(decoded->payload.begin(), decoded->payload.end()), payload);
    EXPECT_FALSE(decoded->truncated);
}

TEST(CaptureFrame, DecodesEveryLinkTypeOfALinuxCapture) {
    expect_datagram(link::ethernet, ethernet(ip_udp(payload)));
    // 802.1Q, then QinQ.
    auto tagged = ethernet(
        concat({std::byte{0}, std::byte{5}, std::byte{8}, std::byte{0}}, ip_udp(payload)), 0x8100);
    expect_datagram(link::ethernet, tagged);
    Bytes sll(14, std::byte{0});
    put16(sll, 0x0800);
    expect_datagram(link::linux_sll, concat(sll, ip_udp(payload)));
    Bytes sll2;
    put16(sll2, 0x0800);
    sll2.resize(20, std::byte{0});
    expect_datagram(link::linux_sll2, concat(sll2, ip_udp(payload)));
    expect_datagram(link::null, concat({std::byte{2}, std::byte{0}, std::byte{0}, std::byte{0}},
                                       ip_udp(payload)));
    expect_datagram(link::loop, concat({std::byte{0}, std::byte{0}, std::byte{0}, std::byte{2}},
                                       ip_udp(payload)));
    expect_datagram(link::raw, ip_udp(payload));
    expect_datagram(link::ipv4, ip_udp(payload));
}

TEST(CaptureFrame, EthernetPaddingIsNotPayload) {
    auto frame = ethernet(ip_udp(payload));
    frame.resize(60, std::byte{0});  // the minimum Ethernet frame
    expect_datagram(link::ethernet, frame);
}

TEST(CaptureFrame, ACaptureCutByTheSnapshotLengthIsTruncated) {
    auto frame = ip_udp(payload);
    frame.pop_back();
    const auto decoded = decode_frame(link::raw, frame);
    ASSERT_TRUE(decoded);
    EXPECT_TRUE(decoded->truncated);
    EXPECT_EQ(decoded->payload.size(), 2u);
}

TEST(CaptureFrame, SaysWhyAFrameHasNoDatagram) {
    const auto skip = [](int link_type, const Bytes& frame) {
        const auto decoded = decode_frame(link_type, frame);
        return decoded ? std::string("decoded") : std::string(to_string(decoded.error()));
    };
    EXPECT_EQ(skip(link::ethernet, ethernet(ip_udp(payload), 0x86DD)), "not_ipv4");
    EXPECT_EQ(skip(42, ip_udp(payload)), "unknown_link");
    auto tcp = ip_udp(payload);
    tcp[9] = std::byte{6};
    EXPECT_EQ(skip(link::raw, tcp), "not_udp");
    EXPECT_EQ(skip(link::raw, ip_udp(payload, 0x2000)), "fragment");  // more fragments
    EXPECT_EQ(skip(link::raw, ip_udp(payload, 0x0010)), "fragment");  // a later one
    auto cut_udp_header = ip_udp(payload);
    cut_udp_header.resize(24);
    EXPECT_EQ(skip(link::raw, cut_udp_header), "malformed");
    auto short_header = ip_udp(payload);
    short_header[0] = std::byte{0x44};  // IHL 4: a 16-byte header
    EXPECT_EQ(skip(link::raw, short_header), "malformed");
    auto long_udp = ip_udp(payload);
    long_udp[25] = std::byte{200};  // a UDP length beyond the IP packet
    EXPECT_EQ(skip(link::raw, long_udp), "malformed");
    EXPECT_EQ(skip(link::linux_sll, Bytes(10, std::byte{0})), "malformed");
    EXPECT_EQ(skip(link::raw, {}), "not_ipv4");
}

TEST(FrameSkip, EveryReasonHasAName) { test::expect_every_value_named(frame_skip_names); }

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::capture
