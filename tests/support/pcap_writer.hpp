#pragma once
/// Writes captures for tshark: UDP datagrams in a pcap file of raw IPv4 (LINKTYPE_RAW), from
/// 127.0.0.1 to 127.0.0.1, each with the capture time the test chooses.

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace eip2mqtt::test {

class PcapWriter {
public:
    /// Creates (or empties) `path` and writes the file header.
    explicit PcapWriter(const std::string& path);
    /// One datagram to UDP port `port` (from the same port), captured at `time_us`
    /// microseconds since 1970 UTC.
    void add(const std::vector<std::byte>& payload, std::uint64_t time_us,
             std::uint16_t port = 18246);
    /// Flushes; false when anything failed to be written.
    bool close();

private:
    std::ofstream out_;
};

/// A capture of one datagram to port 18246, at 1,700,000,000 s.
void write_pcap(const std::string& path, const std::vector<std::byte>& payload);

}  // namespace eip2mqtt::test
