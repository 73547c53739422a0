// Interop: the generated plugin with names Wireshark refuses in field names (spaces, dots,
// non-ASCII), and with 1,000 exchanges: it loads, its fields filter, and tshark decodes 100,000
// datagrams with it.

#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;

constexpr std::uint64_t t0_us = std::uint64_t{1700000000} * 1000000;

const std::string header =
    "gateway:\n  id: scale-test\nmqtt:\n  url: tcp://127.0.0.1:1883\n  base_topic: test\n";

std::string write_plugin(const TempDir& dir, const std::string& config_text) {
    const auto config = dir.write("plant.yaml", config_text);
    const auto plugin = dir.path() + "/eip2mqtt.lua";
    const auto made = run_command({gateway_binary(), "dissector", "-c", config, "-o", plugin}, 60s);
    EXPECT_EQ(made.status, 0) << made.output;
    return plugin;
}

TEST(DissectorScale, NamesWiresharkRefusesAreEscapedInFieldsAndKeptInLabels) {
    TempDir dir;
    const auto plugin = write_plugin(
        dir, header +
                 "exchanges:\n"
                 "  - name: \"Bomba 1.sul\"\n    producer_id: 10.0.0.9\n    exchange_id: 1\n"
                 "    length: 8\n    tags:\n"
                 "      - { name: \"PRESS\xC3\x83O\", address: \"0.0\", type: word, unit: bar }\n"
                 "      - { name: \"temp.\xC2\xB0"
                 "C\", address: \"2.0\", type: int }\n"
                 "      - { name: \"n\xC3\xADvel 2\", address: \"4.0\", type: real, "
                 "unit: \"m\xC2\xB3\" }\n");
    DatagramBuilder builder("10.0.0.9", 1, 8);
    builder.request_id(1)
        .set("0.0", TagType::word, std::uint64_t{1234})
        .set("2.0", TagType::int_, std::int64_t{-40})
        .set("4.0", TagType::real, 2.5f);
    const auto pcap_path = dir.path() + "/names.pcap";
    write_pcap(pcap_path, builder.build());

    const auto decoded = tshark_fields(
        plugin, pcap_path,
        {"eip2mqtt.Bomba_1_sul.PRESS_O", "eip2mqtt.Bomba_1_sul.temp__C",
         "eip2mqtt.Bomba_1_sul.n_vel_2"},
        {"-Y", "eip2mqtt.Bomba_1_sul.PRESS_O > 1000 && eip2mqtt.Bomba_1_sul.temp__C < 0"});
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), 1u) << decoded.output;
    EXPECT_EQ(decoded.rows[0], (std::vector<std::string>{"1", "1234", "-40", "2.5"}));

    // The tree shows the configured names, with their units.
    const auto tree = tshark_run(plugin, pcap_path, {"-O", "eip2mqtt", "-V"});
    ASSERT_EQ(tree.status, 0) << tree.output;
    for (const char* line : {"Bomba 1.sul", "PRESS\xC3\x83O (bar): 1234",
                             "temp.\xC2\xB0"
                             "C: -40",
                             "n\xC3\xADvel 2 (m\xC2\xB3): 2.5"}) {
        EXPECT_NE(tree.output.find(line), std::string::npos) << line << "\n" << tree.output;
    }
}

TEST(DissectorScale, AThousandExchangesAndAHundredThousandDatagrams) {
    constexpr int exchanges = 1000;
    constexpr int rounds = 100;
    std::string yaml = header + "exchanges:\n";
    char name[16];
    for (int e = 0; e < exchanges; ++e) {
        std::snprintf(name, sizeof name, "ex%04d", e);
        yaml += std::string("  - { name: ") + name + ", producer_id: 10.0." +
                std::to_string(e / 250) + "." + std::to_string(e % 250 + 1) +
                ", exchange_id: " + std::to_string(e + 1) +
                ", length: 12, timeout_ms: 0, period_ms: 100,\n"
                "      tags: [ { name: W, address: \"0.0\", type: udint },"
                " { name: R, address: \"4.0\", type: real },"
                " { name: B, address: \"8.3\", type: bit },"
                " { name: I, address: \"10.0\", type: int } ] }\n";
    }
    TempDir dir;
    const auto plugin = write_plugin(dir, yaml);

    // Round r sends every exchange once, 100 us apart, W = exchange x 1000 + round.
    const auto pcap_path = dir.path() + "/plant.pcap";
    PcapWriter pcap(pcap_path);
    for (int r = 0; r < rounds; ++r) {
        for (int e = 0; e < exchanges; ++e) {
            DatagramBuilder builder(
                "10.0." + std::to_string(e / 250) + "." + std::to_string(e % 250 + 1),
                static_cast<std::uint32_t>(e + 1), 12);
            builder.request_id(static_cast<std::uint16_t>(r + 1))
                .set("0.0", TagType::udint, std::uint64_t(e * 1000 + r));
            pcap.add(builder.build(), t0_us + static_cast<std::uint64_t>(r * exchanges + e) * 100);
        }
    }
    ASSERT_TRUE(pcap.close());

    // Exchange 500's datagram of round 42 is frame 42 x 1000 + 500 + 1.
    const auto result = tshark_fields(plugin, pcap_path, {"eip2mqtt.ex0500.W"},
                                      {"-Y", "eip2mqtt.ex0500.W == 500042", "-z", "eip2mqtt,stat"});
    ASSERT_EQ(result.status, 0) << result.output.substr(0, 2000);
    ASSERT_EQ(result.rows.size(), 1u) << result.output.substr(0, 2000);
    EXPECT_EQ(result.rows[0], (std::vector<std::string>{"42501", "500042"}));
    // Every exchange in the statistics, each with all its datagrams and none missed.
    for (const int e : {0, 1, 499, 998, 999}) {
        std::snprintf(name, sizeof name, "ex%04d", e);
        const auto at = result.output.find(std::string("\n") + name + " ");
        ASSERT_NE(at, std::string::npos) << name;
        const auto line = result.output.substr(at + 1, result.output.find('\n', at + 1) - at - 1);
        EXPECT_NE(line.find(" 100 "), std::string::npos) << line;
    }
    std::size_t rows = 0;
    for (std::size_t at = result.output.find("\nex"); at != std::string::npos;
         at = result.output.find("\nex", at + 1)) {
        if (std::isdigit(static_cast<unsigned char>(result.output[at + 3])) != 0) ++rows;
    }
    EXPECT_EQ(rows, static_cast<std::size_t>(exchanges));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
