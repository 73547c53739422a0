// Interop: Wireshark's EGD dissector (tshark) decodes a datagram the gateway produced into
// exactly the header fields its configuration says.

#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// The header time as tshark prints an absolute time in UTC: `Aug  8, 2023 22:52:10.567000680 UTC`.
std::string utc_text(std::uint32_t seconds, std::uint32_t nanoseconds) {
    const std::time_t t = seconds;
    std::tm tm{};
    gmtime_r(&t, &tm);
    char date[64];
    std::strftime(date, sizeof date, "%b %e, %Y %H:%M:%S", &tm);
    char ns[16];
    std::snprintf(ns, sizeof ns, ".%09u", nanoseconds);
    return std::string(date) + ns + " UTC";
}

TEST(TsharkVectors, V3DecodesAsTheProtocolPageSays) {
    // docs/protocol.md §8 V3, written by hand into a pcap: tshark and we read the same header.
    TempDir dir;
    const std::string pcap = dir.path() + "/v3.pcap";
    std::vector<std::byte> v3;
    for (const char* p =
             "0d01294ec0a865d3030000001ac7d26468becb2100000000000000000000000000000000"
             "000034430000da420000dc42";
         *p != '\0'; p += 2) {
        v3.push_back(static_cast<std::byte>(std::stoi(std::string(p, 2), nullptr, 16)));
    }
    write_pcap(pcap, v3);
    ChildProcess tshark({"/usr/bin/tshark", "-r", pcap, "-T", "fields", "-E", "separator=;", "-e",
                         "egd.rid", "-e", "egd.pid", "-e", "egd.time"},
                        {{"TZ", "UTC"}});
    ASSERT_EQ(tshark.wait(30s), 0) << tshark.output();
    EXPECT_NE(tshark.output().find("20009;192.168.101.211;Aug  8, 2023 22:52:10.567000680 UTC"),
              std::string::npos)
        << tshark.output();
}

class TsharkInterop : public GatewayTest {};

TEST_F(TsharkInterop, EgdDissectorDecodesTheProducedHeader) {
    UdpClient capture;
    start(ExchangeYaml::produce("sp", "172.23.21.176", 4242,
                                "127.0.0.1:" + std::to_string(capture.port()))
              .key("signature", "\"2.5\"")
              .period_ms(50)
              .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 1.5")
              .str());
    const auto bytes = capture.receive(5s);
    ASSERT_TRUE(bytes.has_value());
    const auto header = core::wire::decode_datagram(*bytes).value().header;

    const std::string pcap = dir_.path() + "/produced.pcap";
    write_pcap(pcap, *bytes);
    ChildProcess tshark(
        {"/usr/bin/tshark", "-r", pcap,       "-T", "fields",   "-E", "separator=;", "-e",
         "egd.type",        "-e", "egd.ver",  "-e", "egd.rid",  "-e", "egd.pid",     "-e",
         "egd.exid",        "-e", "egd.time", "-e", "egd.stat", "-e", "egd.csig",    "-e",
         "egd.rsrv"},
        {{"TZ", "UTC"}});
    ASSERT_EQ(tshark.wait(30s), 0) << tshark.output();
    const RunResult result{0, tshark.output()};
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
    EXPECT_EQ(fields[4], "0x00001092");  // 4242
    EXPECT_EQ(fields[5], utc_text(header.time_s, header.time_ns));
    EXPECT_EQ(fields[6], "0");
    EXPECT_EQ(fields[7], std::to_string(0x0205));
    EXPECT_EQ(fields[8], "0");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
