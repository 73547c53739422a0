// Interop: `tshark -q -z eip2mqtt,stat` with the generated plugin counts, per exchange, the
// datagrams, periods, jitter, missed, duplicated and late datagrams of a capture whose every
// figure the test chose.

#include <sstream>
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

constexpr std::uint64_t t0_ms = 1700000000000;

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t request_id,
                                std::uint64_t stamped_ms) {
    DatagramBuilder builder("10.0.0.9", exchange_id, 8);
    builder.request_id(request_id)
        .timestamp(static_cast<std::uint32_t>(stamped_ms / 1000),
                   static_cast<std::uint32_t>(stamped_ms % 1000 * 1000000));
    return builder.build();
}

/// The words of the statistics row whose first word is `label`.
std::vector<std::string> row_of(const std::string& output, const std::string& label) {
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::vector<std::string> row;
        for (std::string word; words >> word;) row.push_back(word);
        if (!row.empty() && row[0] == label) return row;
    }
    return {};
}

TEST(DissectorStatistics, CountsWhatWasSentPerExchange) {
    TempDir dir;
    const auto config = dir.write(
        "stat.yaml",
        "gateway:\n  id: stat-test\nmqtt:\n  url: tcp://127.0.0.1:1883\n  base_topic: test\n"
        "exchanges:\n"
        "  - { name: pump, producer_id: 10.0.0.9, exchange_id: 5, length: 8, period_ms: 100,\n"
        "      timeout_ms: 0 }\n");
    const auto plugin = dir.path() + "/eip2mqtt.lua";
    const auto made = run_command({gateway_binary(), "dissector", "-c", config, "-o", plugin}, 30s);
    ASSERT_EQ(made.status, 0) << made.output;

    // pump: request ids 1-5 every 100 ms, 8 at 700 ms (6 and 7 missed), 8 again at 710 ms (a
    // duplicate), 9 at 800 ms, and 5 at 900 ms stamped back then (late): 9 datagrams.
    // Periods 100 x 4, 300, 10, 90, 100: mean 900 / 8 = 112.5, min 10, max 300. Jitter against
    // the configured 100 ms, J += (|P - 100| - J) / 16: 0 x 4, then 12.5, 17.34375,
    // 16.884765625, 15.8294677734375.
    // An exchange nobody configured, 10.0.0.9/99: two datagrams a second apart.
    const auto pcap_path = dir.path() + "/stat.pcap";
    PcapWriter pcap(pcap_path);
    const std::pair<std::uint16_t, std::uint64_t> pump[] = {
        {1, 0}, {2, 100}, {3, 200}, {4, 300}, {5, 400}, {8, 700}, {8, 710}, {9, 800}, {5, 900}};
    pcap.add(datagram(99, 1, t0_ms), t0_ms * 1000);
    for (const auto& [rid, at] : pump) {
        const auto stamped = at == 900 ? t0_ms + 400 : t0_ms + at;
        pcap.add(datagram(5, rid, stamped), (t0_ms + at) * 1000);
    }
    pcap.add(datagram(99, 2, t0_ms + 1000), (t0_ms + 1000) * 1000);
    ASSERT_TRUE(pcap.close());

    const auto result = tshark_run(plugin, pcap_path, {"-q", "-z", "eip2mqtt,stat"});
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_EQ(row_of(result.output, "exchange"),
              (std::vector<std::string>{"exchange", "datagrams", "period", "min", "max", "jitter",
                                        "missed", "duplicates", "out_of_order"}))
        << result.output;
    EXPECT_EQ(row_of(result.output, "pump"),
              (std::vector<std::string>{"pump", "9", "112.500", "10.000", "300.000", "15.829", "2",
                                        "1", "1"}))
        << result.output;
    EXPECT_EQ(row_of(result.output, "10.0.0.9/99"),
              (std::vector<std::string>{"10.0.0.9/99", "2", "1000.000", "1000.000", "1000.000",
                                        "0.000", "0", "0", "0"}))
        << result.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
