// Interop: the generated plugin decodes every PDU of the command protocol on port 7937
// (docs/protocol.md §9) into its fields: the vectors of §9.6, field by field as the page
// describes them.

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "tests/core/command/command_vectors.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
namespace v = command_vectors;

struct Expected {
    std::string_view hex;
    std::map<std::string, std::string> fields;  ///< without the `eip2mqtt_cmd.` prefix
};

const std::vector<Expected> vectors = {
    {v::c1_retrieve_config_request,
     {{"type", "3"},
      {"request_id", "4369"},
      {"producer_id", "105.102.0.200"},
      {"exchange_id", "12001"}}},
    {v::c2_retrieve_config_response,
     {{"type", "4"},
      {"version", "1"},
      {"length", "76"},
      {"period_ms", "1600"},
      {"destination_type", "1"},
      {"destination", "105.102.0.200"},
      {"state", "2"},
      {"exchange_length", "1400"},
      {"data_port", "18246"},
      {"signature", "0.0"},
      {"mode", "2"}}},
    {v::c3_capabilities_request, {{"type", "9"}, {"producer_id", "10.0.0.5"}}},
    {v::c4_capabilities_response,
     {{"type", "10"},
      {"max_exchanges", "4"},
      {"capabilities", "0x00000007"},
      {"identification", "eip2mqtt 0.1.0"}}},
    {v::c5_summary_request, {{"type", "7"}, {"index", "0"}}},
    {v::c6_summary_response,
     {{"type", "8"},
      {"producer_id", "10.0.0.5,10.0.0.5,10.0.0.9"},
      {"total", "2"},
      {"count", "2"},
      {"exchange_id", "7,3"},
      {"entry.mode", "1,2"},
      {"state", "2,1"},
      {"period_ms", "100,250"}}},
    {v::c7_statistics_request, {{"type", "15"}, {"exchange_id", "7"}}},
    {v::c8_statistics_response,
     {{"type", "16"},
      {"stats.due_ms", "40"},
      {"stats.state", "2"},
      {"stats.length", "8"},
      {"stats.messages", "1234"},
      {"stats.missed", "0"},
      {"stats.refresh_errors", "0"}}},
    {v::c9_read_request,
     {{"type", "32"},
      {"cells", "1"},
      {"producer_id", "10.0.0.5"},
      {"exchange_id", "7"},
      {"cell.offset", "2"},
      {"cell.length", "3"},
      {"cell.data", ""}}},
    {v::c10_read_response, {{"type", "33"}, {"cell.data", "112233"}}},
    {v::c11_write_request,
     {{"type", "34"}, {"cell.offset", "4"}, {"cell.length", "2"}, {"cell.data", "e803"}}},
    {v::c12_write_response, {{"type", "35"}, {"cells", "0"}, {"cell.offset", ""}}},
    {v::c13_masked_write_request,
     {{"type", "36"}, {"cell.offset", "0"}, {"cell.data", "01"}, {"cell.mask", "05"}}},
    {v::c14_read_without_cells, {{"type", "32"}, {"cells", "0"}}},
    {v::c15_nak,
     {{"type", "18"},
      {"producer_id", "10.0.0.5"},
      {"exchange_id", "7"},
      {"nak.reason", "6"},
      {"nak.error", "malformed"}}},
    {v::c16_challenge,
     {{"type", "8"}, {"status", "9"}, {"request_id", "6"}, {"token", "0x00abcdef"}}},
};

TEST(DissectorCommands, DecodesEveryPduOfTheProtocolPage) {
    TempDir dir;
    const auto config =
        dir.write("cmd.yaml",
                  "gateway:\n  id: cmd-test\nmqtt:\n  url: tcp://127.0.0.1:1883\n"
                  "  base_topic: test\nexchanges:\n"
                  "  - { name: any, producer_id: 10.0.0.5, exchange_id: 7, length: 8 }\n");
    const auto plugin = dir.path() + "/eip2mqtt.lua";
    const auto made = run_command({gateway_binary(), "dissector", "-c", config, "-o", plugin}, 30s);
    ASSERT_EQ(made.status, 0) << made.output;

    const auto pcap_path = dir.path() + "/commands.pcap";
    PcapWriter pcap(pcap_path);
    for (std::size_t i = 0; i < vectors.size(); ++i) {
        pcap.add(from_hex(vectors[i].hex), (std::uint64_t{1700000000} + i) * 1000000, 7937);
    }
    ASSERT_TRUE(pcap.close());

    std::vector<std::string> names;
    for (const auto& vector : vectors) {
        for (const auto& [name, value] : vector.fields) {
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    std::vector<std::string> fields;
    for (const auto& name : names) fields.push_back("eip2mqtt_cmd." + name);
    const auto decoded = tshark_fields(plugin, pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), vectors.size()) << decoded.output;
    for (std::size_t i = 0; i < vectors.size(); ++i) {
        for (const auto& [name, value] : vectors[i].fields) {
            const auto column = std::find(names.begin(), names.end(), name) - names.begin();
            EXPECT_EQ(decoded.rows[i][1 + column], value) << "C" << i + 1 << " " << name;
        }
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
