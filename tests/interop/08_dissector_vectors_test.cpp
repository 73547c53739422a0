// Interop: the test vectors of docs/protocol.md §8 (tests/core/vectors.hpp), each alone in a
// capture, read by tshark with the plugin generated for a configuration that declares their
// exchanges and tags as the vectors describe them: every header field and every tag value is
// the one the vector states (and the core tests decode); a vector the gateway refuses raises the
// plugin's expert entry instead, and a valid one raises none.

#include <array>
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "tests/core/vectors.hpp"
#include "tests/support/dissector_values.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

constexpr std::uint16_t data_port = 18246;

const std::array<std::string, 6> header_fields = {"eip2mqtt.request_id",  "eip2mqtt.producer_id",
                                                  "eip2mqtt.exchange_id", "eip2mqtt.timestamp",
                                                  "eip2mqtt.status",      "eip2mqtt.signature"};
using Header = std::array<std::string, 6>;
const Header no_header{};

struct VectorTag {
    const char* name;
    const char* address;
    const char* type;
};

/// V1 and V2 (producer 192.168.1.1, exchange 1, 15 bytes): the bits of byte 0, the 16-bit value
/// at 1.0, the four bytes at 3.0 as a `dint` and as a `real`, the `lint` at 7.0.
constexpr VectorTag point_list_tags[] = {
    {"B0", "0.0", "bit"},        {"B1", "0.1", "bit"},       {"B2", "0.2", "bit"},
    {"B3", "0.3", "bit"},        {"B4", "0.4", "bit"},       {"B5", "0.5", "bit"},
    {"B6", "0.6", "bit"},        {"B7", "0.7", "bit"},       {"COUNT", "1.0", "word"},
    {"COUNT_INT", "1.0", "int"}, {"AS_DINT", "3.0", "dint"}, {"AS_REAL", "3.0", "real"},
    {"TOTAL", "7.0", "lint"},
};
/// V3 (producer 192.168.101.211, exchange 3): four `real`s.
constexpr VectorTag reals_tags[] = {
    {"R0", "0.0", "real"}, {"R4", "4.0", "real"}, {"R8", "8.0", "real"}, {"R12", "12.0", "real"}};

/// V4 (the first 20 bytes of a header) and V5 (no data) carry no data: the plugin refuses them
/// before it looks their exchange up, so the configuration needs none for them.
std::string vectors_config() {
    auto point_list = ExchangeYaml::consume("point_list", "192.168.1.1", 1).length(15);
    for (const auto& tag : point_list_tags) point_list.tag(tag.name, tag.address, tag.type);
    auto reals = ExchangeYaml::consume("reals", "192.168.101.211", 3).length(16);
    for (const auto& tag : reals_tags) reals.tag(tag.name, tag.address, tag.type);
    return "gateway:\n  id: vectors-test\nmqtt:\n  url: tcp://127.0.0.1:1883\n"
           "  base_topic: test\neip:\n  port: " +
           std::to_string(data_port) + "\nexchanges:\n" + point_list.str() + reals.str();
}

/// Every tag field of the configuration.
std::vector<std::string> tag_fields() {
    std::vector<std::string> fields;
    for (const auto& tag : point_list_tags)
        fields.push_back(std::string("eip2mqtt.point_list.") + tag.name);
    for (const auto& tag : reals_tags) fields.push_back(std::string("eip2mqtt.reals.") + tag.name);
    return fields;
}

struct VectorCase {
    std::string name;
    std::vector<std::byte> bytes;
    std::uint64_t captured_us;  ///< capture time: the vector's own timestamp when it has one
    Header header;              ///< as tshark shows it; all empty when the plugin shows none
    /// Tag field -> value as tshark shows it; every other tag field is absent.
    std::map<std::string, std::string> tags;
    std::string expert;  ///< the plugin's expert message, "" for none
};

void PrintTo(const VectorCase& vector, std::ostream* out) { *out << vector.name; }

std::uint64_t at_us(std::uint32_t seconds, std::uint32_t micros = 0) {
    return std::uint64_t{seconds} * 1000000 + micros;
}

/// V1 and V2 share their header and all but the four bytes at 3.0.
const Header v1_header{"108", "192.168.1.1", "1", "Sep 20, 2023 17:41:18.000000000 UTC",
                       "0",   "0.0"};
std::map<std::string, std::string> point_list_values(const std::string& as_dint,
                                                     const std::string& as_real) {
    std::map<std::string, std::string> values;
    const char* const bits[] = {"1", "1", "1", "0", "0", "1", "1", "1"};  // byte E7
    for (int b = 0; b < 8; ++b) values["eip2mqtt.point_list.B" + std::to_string(b)] = bits[b];
    values["eip2mqtt.point_list.COUNT"] = "90";
    values["eip2mqtt.point_list.COUNT_INT"] = "90";
    values["eip2mqtt.point_list.AS_DINT"] = as_dint;
    values["eip2mqtt.point_list.AS_REAL"] = as_real;
    values["eip2mqtt.point_list.TOTAL"] = "956000";
    return values;
}

std::vector<VectorCase> data_vectors() {
    const auto v1_at = at_us(utc_seconds(2023, 9, 20, 17, 41, 18));
    // V1: the seed-style integer "real": 65900 as a dint, the subnormal 9.2346e-41 as a real
    // (tshark prints six digits).
    // V2: 65900.0 as a real, whose bytes (0x4780B600) a dint reads as 1199617536.
    // V4 as the wire tests read it: completed with zeros to a header, and no data.
    auto v4_header = from_hex(vectors::v4);
    v4_header.resize(32);
    return {
        {"V1", from_hex(vectors::v1), v1_at, v1_header, point_list_values("65900", "9.23456e-41"),
         ""},
        {"V2", from_hex(vectors::v2), v1_at, v1_header, point_list_values("1199617536", "65900"),
         ""},
        {"V3",
         from_hex(vectors::v3),
         at_us(utc_seconds(2023, 8, 8, 22, 52, 10), 567000),
         {"20009", "192.168.101.211", "3", "Aug  8, 2023 22:52:10.567000680 UTC", "0", "0.0"},
         {{"eip2mqtt.reals.R0", "0"},
          {"eip2mqtt.reals.R4", "180"},
          {"eip2mqtt.reals.R8", "109"},
          {"eip2mqtt.reals.R12", "110"}},
         ""},
        {"V4",
         from_hex(vectors::v4),
         at_us(utc_seconds(2023, 2, 3, 16, 12, 35), 260970),
         no_header,
         {},
         "Not a data datagram: too short, or not PDU type 0x0D version 1"},
        {"V4CompletedToAHeader",
         v4_header,
         at_us(utc_seconds(2023, 2, 3, 16, 12, 35), 260970),
         {"13969", "172.23.21.176", "1", "Feb  3, 2023 16:12:35.260970100 UTC", "0", "0.0"},
         {},
         "0 data bytes: 1 to 1400 expected"},
        {"V5",
         from_hex(vectors::v5),
         at_us(1700000000),
         {"1", "10.0.0.5", "7", "Jan  1, 1970 00:00:00.000000000 UTC", "0", "2.5"},
         {},
         "0 data bytes: 1 to 1400 expected"},
    };
}

/// V7: V2 changed as the gateway must refuse it, or cut to a length it must refuse.
std::vector<VectorCase> refused_vectors() {
    const auto v1_at = at_us(utc_seconds(2023, 9, 20, 17, 41, 18));
    const char* const not_data = "Not a data datagram: too short, or not PDU type 0x0D version 1";
    auto swapped = from_hex(vectors::v2);
    swapped[0] = std::byte{0x01};
    swapped[1] = std::byte{0x0D};
    auto cut_31 = from_hex(vectors::v2);
    cut_31.resize(31);
    auto cut_32 = from_hex(vectors::v2);
    cut_32.resize(32);
    auto exchange_124 = from_hex(vectors::v2);
    exchange_124[8] = std::byte{124};
    auto header_124 = v1_header;
    header_124[2] = "124";
    auto one_byte_less = from_hex(vectors::v2);
    one_byte_less.pop_back();
    // The lint at 7.0 would end past the 14th byte: it is left out.
    auto all_but_total = point_list_values("1199617536", "65900");
    all_but_total.erase("eip2mqtt.point_list.TOTAL");
    return {
        {"V2WithPduTypeBytesSwapped", swapped, v1_at, no_header, {}, not_data},
        {"V2CutTo31Bytes", cut_31, v1_at, no_header, {}, not_data},
        {"V2CutTo32Bytes", cut_32, v1_at, v1_header, {}, "0 data bytes: 1 to 1400 expected"},
        {"V2WithExchangeId124",
         exchange_124,
         v1_at,
         header_124,
         {},
         "No configured exchange has producer id 192.168.1.1 and exchange id 124"},
        {"V2WithOneDataByteLess", one_byte_less, v1_at, v1_header, all_but_total,
         "14 data bytes, configured 15"},
    };
}

class DissectorVectors : public ::testing::TestWithParam<VectorCase> {};

TEST_P(DissectorVectors, TsharkShowsEveryHeaderFieldAndTagAsTheVectorStates) {
    const auto& vector = GetParam();
    TempDir dir;
    const auto plugin = write_dissector(dir.write("vectors.yaml", vectors_config()), dir.path());
    const auto pcap_path = dir.path() + "/" + vector.name + ".pcap";
    PcapWriter pcap(pcap_path);
    pcap.add(vector.bytes, vector.captured_us, data_port);
    ASSERT_TRUE(pcap.close());

    std::vector<std::string> fields(header_fields.begin(), header_fields.end());
    fields.push_back("_ws.expert.message");
    const auto tags = tag_fields();
    fields.insert(fields.end(), tags.begin(), tags.end());
    const auto decoded = tshark_fields(plugin, pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), 1u) << decoded.output;
    const auto& row = decoded.rows[0];
    for (std::size_t f = 0; f < header_fields.size(); ++f) {
        EXPECT_EQ(row[1 + f], vector.header[f]) << header_fields[f];
    }
    EXPECT_EQ(row[1 + header_fields.size()], vector.expert);
    for (std::size_t t = 0; t < tags.size(); ++t) {
        const auto expected = vector.tags.find(tags[t]);
        EXPECT_EQ(row[2 + header_fields.size() + t],
                  expected == vector.tags.end() ? "" : expected->second)
            << tags[t];
    }
}

INSTANTIATE_TEST_SUITE_P(DataPort, DissectorVectors, ::testing::ValuesIn(data_vectors()),
                         [](const auto& info) { return info.param.name; });
INSTANTIATE_TEST_SUITE_P(Refused, DissectorVectors, ::testing::ValuesIn(refused_vectors()),
                         [](const auto& info) { return info.param.name; });

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
