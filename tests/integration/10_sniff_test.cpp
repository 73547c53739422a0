// `eip2mqtt sniff` decodes headers and tags and counts gaps and duplicates per exchange.

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;

/// A configuration that is never run as a gateway: sniff only reads its exchanges.
std::string config(std::uint16_t port) {
    return "gateway:\n"
           "  id: sniff-gw\n"
           "mqtt:\n"
           "  url: tcp://127.0.0.1:1\n"
           "  base_topic: test\n"
           "eip:\n"
           "  bind: 127.0.0.1\n"
           "  port: " +
           std::to_string(port) +
           "\n"
           "exchanges:\n" +
           ExchangeYaml::consume("turbine1", "10.0.0.9", 3)
               .length(8)
               .period_ms(100)
               .tag("PRESSAO", "0.0", "int")
               .tag("TEMP", "2.0", "real")
               .tag("RUN", "6.3", "bit")
               .str() +
           ExchangeYaml::produce("setpoints", "10.0.0.50", 10, "127.0.0.1:9")
               .period_ms(100)
               .tag("SPEED_SP", "0.0", "real", "writable: true")
               .str();
}

std::vector<std::byte> turbine(std::uint16_t rid, std::int64_t pressure) {
    return DatagramBuilder("10.0.0.9", 3, 8)
        .request_id(rid)
        .timestamp(1695231678, 500000000)
        .signature(1, 0)
        .set("0.0", TagType::int_, pressure)
        .set("2.0", TagType::real, 12.5F)
        .set("6.3", TagType::bit, true)
        .build();
}

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> result;
    for (std::string word; in >> word;) result.push_back(word);
    return result;
}

/// The cells of the last statistics row of `exchange`, by column header.
std::map<std::string, std::string> last_row(const std::string& output,
                                            const std::string& exchange) {
    std::istringstream in(output);
    std::vector<std::string> header;
    std::map<std::string, std::string> row;
    for (std::string line; std::getline(in, line);) {
        const auto cells = words(line);
        if (cells.empty()) continue;
        if (cells[0] == "exchange") header = cells;
        if (cells[0] == exchange && cells.size() == header.size()) {
            row.clear();
            for (std::size_t i = 0; i < cells.size(); ++i) row[header[i]] = cells[i];
        }
    }
    return row;
}

/// The load of the datagrams DecodesHeadersAndTagsAndCountsGapsAndDuplicates sends: 7 of 4 x
/// 40, 36, 34 and 20 bytes, each with 66 bytes of Ethernet, IP and UDP around it (98 - the 32
/// bytes of EIP header it holds); configured: turbine1 (8 bytes) and setpoints (4 bytes), each
/// every 100 ms: 10 x 106 x 8 + 10 x 102 x 8 bit/s.
void expect_load(const std::string& output) {
    const auto load = output.rfind("load: measured ");
    ASSERT_NE(load, std::string::npos) << output;
    const auto load_line = output.substr(load, output.find('\n', load) - load);
    EXPECT_NE(load_line.find("(7 datagrams, 712 bytes on the wire since start)"), std::string::npos)
        << load_line;
    EXPECT_NE(load_line.find("configured 20 datagrams/s, 16640 bit/s"), std::string::npos)
        << load_line;
}

TEST(Sniff, DecodesHeadersAndTagsAndCountsGapsAndDuplicates) {
    TempDir dir;
    const auto port = free_udp_port();
    const auto path = dir.write("sniff.yaml", config(port));
    ChildProcess sniff({gateway_binary(), "sniff", "--port", std::to_string(port), "--duration",
                        "3", "--interval", "0.5", "-c", path});
    ASSERT_TRUE(sniff.wait_for_output("sniffing")) << sniff.output();

    UdpClient udp;
    udp.send_to(port, turbine(1, 100));
    udp.send_to(port, turbine(2, 101));
    udp.send_to(port, turbine(4, 103));  // rid 3 missed
    udp.send_to(port, turbine(4, 103));  // duplicate
    udp.send_to(port, DatagramBuilder("10.0.0.50", 10, 4)
                          .request_id(7)
                          .set("0.0", TagType::real, 3000.5F)
                          .build());
    udp.send_to(port, DatagramBuilder("10.0.0.77", 5, 2).request_id(1).build());
    auto short_one = turbine(5, 104);
    short_one.resize(20);
    udp.send_to(port, short_one);

    ASSERT_EQ(sniff.wait(std::chrono::seconds(10)), 0) << sniff.output();
    const auto output = sniff.output();

    // Header fields.
    for (const auto* text :
         {"127.0.0.1:", " rid=1 producer=10.0.0.9 exchange=3 time=2023-09-20T17:41:18.500000000Z",
          "status=0 signature=1.0 length=8", " rid=4 ", " duplicate"}) {
        EXPECT_NE(output.find(text), std::string::npos) << text << "\nin:\n" << output;
    }
    // Decoded tags of a consumed and a produced exchange; an unconfigured one has none.
    EXPECT_NE(output.find("[turbine1] PRESSAO=100 TEMP=12.5 RUN=true"), std::string::npos)
        << output;
    EXPECT_NE(output.find("[turbine1] PRESSAO=103 "), std::string::npos) << output;
    EXPECT_NE(output.find("rid=7 producer=10.0.0.50 exchange=10"), std::string::npos) << output;
    EXPECT_NE(output.find("[setpoints] SPEED_SP=3000.5"), std::string::npos) << output;
    EXPECT_NE(output.find("producer=10.0.0.77 exchange=5"), std::string::npos) << output;
    EXPECT_NE(output.find("dropped=too_short length=20"), std::string::npos) << output;

    const auto row = last_row(output, "turbine1");
    ASSERT_FALSE(row.empty()) << output;
    EXPECT_EQ(row.at("received"), "4");
    EXPECT_EQ(row.at("missed"), "1");
    EXPECT_EQ(row.at("duplicates"), "1");
    EXPECT_EQ(row.at("out_of_order"), "0");
    EXPECT_NE(row.at("period_ms"), "-");  // three samples: a mean period
    EXPECT_FALSE(last_row(output, "10.0.0.77/5").empty()) << output;
    EXPECT_NE(output.find("dropped: too_short=1"), std::string::npos) << output;

    expect_load(output);
}

TEST(Sniff, StopsOnSigterm) {
    const auto port = free_udp_port();
    ChildProcess sniff(
        {gateway_binary(), "sniff", "--port", std::to_string(port), "--bind", "127.0.0.1"});
    ASSERT_TRUE(sniff.wait_for_output("sniffing 127.0.0.1:" + std::to_string(port)))
        << sniff.output();
    UdpClient udp;
    udp.send_to(port, turbine(1, 100));
    ASSERT_TRUE(sniff.wait_for_output("rid=1 producer=10.0.0.9")) << sniff.output();
    sniff.signal(SIGTERM);
    EXPECT_EQ(sniff.wait(std::chrono::seconds(5)), 0) << sniff.output();
    // Without a configuration: headers only, the exchange named by its key.
    EXPECT_EQ(sniff.output().find("PRESSAO"), std::string::npos);
    EXPECT_FALSE(last_row(sniff.output(), "10.0.0.9/3").empty()) << sniff.output();
}

TEST(Sniff, WithoutThePrivilegeToCaptureSaysHowToGetItAndNeverBindsThePort) {
    // setpriv takes CAP_NET_RAW out of the bounding set: even root then runs sniff without it.
    if (::access("/usr/bin/setpriv", X_OK) != 0) GTEST_SKIP() << "no /usr/bin/setpriv";
    const auto port = free_udp_port();
    const auto result =
        run_command({"/usr/bin/setpriv", "--bounding-set", "-net_raw", "--", gateway_binary(),
                     "sniff", "--port", std::to_string(port), "--duration", "5"},
                    std::chrono::seconds(30));
    EXPECT_EQ(result.status, 1) << result.output;
    for (const auto* text : {"needs the CAP_NET_RAW capability", "sudo eip2mqtt sniff",
                             "setcap cap_net_raw,cap_net_admin+eip /"}) {
        EXPECT_NE(result.output.find(text), std::string::npos) << text << "\nin:\n"
                                                               << result.output;
    }
    // It never fell back to a socket on the port, which would take datagrams from a gateway.
    EXPECT_EQ(result.output.find("sniffing"), std::string::npos) << result.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
