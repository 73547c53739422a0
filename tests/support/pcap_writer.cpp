#include "tests/support/pcap_writer.hpp"

#include <array>

namespace eip2mqtt::test {
namespace {

template <class T>
void put(std::ofstream& out, T value) {
    out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

void put_be16(std::ofstream& out, std::uint16_t value) {
    const std::array<char, 2> bytes{static_cast<char>(value >> 8), static_cast<char>(value & 0xFF)};
    out.write(bytes.data(), bytes.size());
}

}  // namespace

PcapWriter::PcapWriter(const std::string& path) : out_(path, std::ios::binary | std::ios::trunc) {
    put<std::uint32_t>(out_, 0xa1b2c3d4);  // magic: microsecond timestamps
    put<std::uint16_t>(out_, 2);
    put<std::uint16_t>(out_, 4);
    put<std::int32_t>(out_, 0);
    put<std::uint32_t>(out_, 0);
    put<std::uint32_t>(out_, 65535);
    put<std::uint32_t>(out_, 101);  // LINKTYPE_RAW
}

void PcapWriter::add(const std::vector<std::byte>& payload, std::uint64_t time_us,
                     std::uint16_t port) {
    const auto udp_length = static_cast<std::uint16_t>(8 + payload.size());
    const auto ip_length = static_cast<std::uint16_t>(20 + udp_length);
    put<std::uint32_t>(out_, static_cast<std::uint32_t>(time_us / 1000000));
    put<std::uint32_t>(out_, static_cast<std::uint32_t>(time_us % 1000000));
    put<std::uint32_t>(out_, ip_length);
    put<std::uint32_t>(out_, ip_length);
    // IPv4, no options, don't fragment, TTL 64, UDP, no checksum, 127.0.0.1 to 127.0.0.1.
    const std::array<std::uint8_t, 20> ip{0x45,
                                          0,
                                          static_cast<std::uint8_t>(ip_length >> 8),
                                          static_cast<std::uint8_t>(ip_length & 0xFF),
                                          0,
                                          0,
                                          0x40,
                                          0,
                                          64,
                                          17,
                                          0,
                                          0,
                                          127,
                                          0,
                                          0,
                                          1,
                                          127,
                                          0,
                                          0,
                                          1};
    out_.write(reinterpret_cast<const char*>(ip.data()), ip.size());
    put_be16(out_, port);
    put_be16(out_, port);
    put_be16(out_, udp_length);
    put_be16(out_, 0);  // no UDP checksum
    out_.write(reinterpret_cast<const char*>(payload.data()),
               static_cast<std::streamsize>(payload.size()));
}

bool PcapWriter::close() {
    out_.close();
    return !out_.fail();
}

void write_pcap(const std::string& path, const std::vector<std::byte>& payload) {
    PcapWriter pcap(path);
    pcap.add(payload, std::uint64_t{1700000000} * 1000000);
    pcap.close();
}

}  // namespace eip2mqtt::test
