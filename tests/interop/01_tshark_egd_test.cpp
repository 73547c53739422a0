// Interop: Wireshark's EGD dissector (tshark) decodes a datagram the gateway produced into
// exactly the header fields its configuration says.

#include <arpa/inet.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

template <class T>
void put(std::ofstream& out, T value) {
    out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

/// Writes one UDP datagram (to port 18246) in a pcap file of raw IPv4 (LINKTYPE_RAW).
void write_pcap(const std::string& path, const std::vector<std::byte>& payload) {
    std::ofstream out(path, std::ios::binary);
    put<std::uint32_t>(out, 0xa1b2c3d4);  // magic, microseconds
    put<std::uint16_t>(out, 2);
    put<std::uint16_t>(out, 4);
    put<std::int32_t>(out, 0);
    put<std::uint32_t>(out, 0);
    put<std::uint32_t>(out, 65535);
    put<std::uint32_t>(out, 101);  // LINKTYPE_RAW
    const std::uint16_t udp_length = static_cast<std::uint16_t>(8 + payload.size());
    const std::uint16_t ip_length = static_cast<std::uint16_t>(20 + udp_length);
    put<std::uint32_t>(out, 1700000000);
    put<std::uint32_t>(out, 0);
    put<std::uint32_t>(out, ip_length);
    put<std::uint32_t>(out, ip_length);
    const std::uint8_t ip[20] = {0x45, 0, static_cast<std::uint8_t>(ip_length >> 8),
                                 static_cast<std::uint8_t>(ip_length & 0xFF), 0, 0, 0x40, 0, 64,
                                 17, 0, 0, 127, 0, 0, 1, 127, 0, 0, 1};
    out.write(reinterpret_cast<const char*>(ip), sizeof ip);
    put<std::uint16_t>(out, htons(18246));
    put<std::uint16_t>(out, htons(18246));
    put<std::uint16_t>(out, htons(udp_length));
    put<std::uint16_t>(out, 0);  // no UDP checksum
    out.write(reinterpret_cast<const char*>(payload.data()),
              static_cast<std::streamsize>(payload.size()));
}

class TsharkInterop : public GatewayTest {};

TEST_F(TsharkInterop, EgdDissectorDecodesTheProducedHeader) {
    UdpClient capture;
    start(R"(  - name: sp
    direction: produce
    producer_id: 172.23.21.176
    exchange_id: 4242
    signature: "2.5"
    destination: 127.0.0.1:)" + std::to_string(capture.port()) + R"(
    period_ms: 50
    topic: sp
    tags:
      - { name: SPEED_SP, address: "0.0", type: real, writable: true, initial: 1.5 }
)");
    const auto bytes = capture.receive(5s);
    ASSERT_TRUE(bytes.has_value());
    const auto header = core::wire::decode_datagram(*bytes).value().header;

    const std::string pcap = dir_.path() + "/produced.pcap";
    write_pcap(pcap, *bytes);
    const auto result = run_command(
        {"/usr/bin/tshark", "-r", pcap, "-T", "fields", "-E", "separator=;", "-e", "egd.type",
         "-e", "egd.ver", "-e", "egd.rid", "-e", "egd.pid", "-e", "egd.exid", "-e", "egd.time",
         "-e", "egd.stat", "-e", "egd.csig", "-e", "egd.rsrv"},
        30s);
    ASSERT_EQ(result.status, 0) << result.output;
    std::string fields_line;
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        if (line.find(';') != std::string::npos) fields_line = line;
    }
    std::vector<std::string> fields;
    std::istringstream split(fields_line);
    for (std::string field; std::getline(split, field, ';');) fields.push_back(field);
    ASSERT_EQ(fields.size(), 9u) << result.output;
    EXPECT_EQ(fields[0], "13");
    EXPECT_EQ(fields[1], "1");
    EXPECT_EQ(fields[2], std::to_string(header.request_id));
    EXPECT_EQ(fields[3], "172.23.21.176");
    EXPECT_EQ(fields[4], "4242");
    // tshark prints the absolute time; its seconds since the epoch must be the header's.
    EXPECT_FALSE(fields[5].empty());
    EXPECT_EQ(fields[6], "0");
    EXPECT_EQ(fields[7], std::to_string(0x0205));
    EXPECT_EQ(fields[8], "0");
}

}  // namespace
}  // namespace eip2mqtt::test
