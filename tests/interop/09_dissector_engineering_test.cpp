// Interop: a scaled tag in the generated Wireshark plugin shows its raw field and, beside it,
// its engineering value, and tshark's engineering value agrees with what the gateway published
// for the same datagrams (linear with clamp, square root, gain and offset). An array shows
// each element, a string its Latin-1 text.

#include <ctime>
#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/dissector_values.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;

struct Raw {
    std::int64_t level;
    std::uint64_t flow;
    std::int64_t oil;
    float temp;
};

// Inside the ranges, beyond them (clamped, and a square root below its zero), and a real.
constexpr Raw raws[] = {{8000, 16384, 650, 12.5f},
                        {32767, 0, -32768, -1.0f},
                        {-5, 65535, 2147483647, 1e30f},
                        {16001, 1, 1, 0.1f}};

class DissectorEngineering : public GatewayTest {};

TEST_F(DissectorEngineering, TsharkShowsRawAndEngineeringValuesAsTheGatewayPublished) {
    start(ExchangeYaml::consume("tank", "10.1.2.3", 77)
              .length(16)
              .timeout_ms(0)
              .tag("LEVEL", "0.0", "int",
                   "unit: '%', scale: { raw: [0, 32000], eu: [0, 100], clamp: true }, "
                   "publish_raw: true")
              .tag("FLOW", "2.0", "word", "scale: { raw: [100, 65535], eu: [0, 500], sqrt: true }")
              .tag("OIL", "4.0", "dint", "scale: { gain: 0.1, offset: -40 }")
              .tag("TEMP", "8.0", "real", "scale: { raw: [0, 100], eu: [32, 212] }")
              .tag("MARKER", "12.0", "word")
              .str());
    const auto now_s = static_cast<std::uint32_t>(std::time(nullptr));
    const std::string pcap_path = dir_.path() + "/tank.pcap";
    PcapWriter pcap(pcap_path);
    for (std::size_t i = 0; i < std::size(raws); ++i) {
        const auto& r = raws[i];
        const auto bytes = DatagramBuilder("10.1.2.3", 77, 16)
                               .request_id(static_cast<std::uint16_t>(1 + i))
                               .timestamp(now_s, 0)
                               .set("0.0", TagType::int_, Value{r.level})
                               .set("2.0", TagType::word, Value{r.flow})
                               .set("4.0", TagType::dint, Value{r.oil})
                               .set("8.0", TagType::real, Value{r.temp})
                               .set("12.0", TagType::word, Value{std::uint64_t{1 + i}})
                               .build();
        send(bytes);
        pcap.add(bytes, (std::uint64_t{now_s} * 1000 + i) * 1000, udp_port_);
        expect_field(topic("tank/MARKER"), "value", std::to_string(1 + i));
    }
    ASSERT_TRUE(pcap.close());

    const char* const names[] = {"LEVEL", "FLOW", "OIL", "TEMP"};
    std::vector<std::string> fields{"eip2mqtt.tank.LEVEL"};
    for (const auto* name : names) fields.push_back(std::string("eip2mqtt.tank.") + name + ".eu");
    const auto decoded =
        tshark_fields(write_dissector(config_path_, dir_.path()), pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), std::size(raws)) << decoded.output;
    for (std::size_t i = 0; i < std::size(raws); ++i) {
        const auto& row = decoded.rows[i];
        // Column 0 is the frame's; the fields follow in the order asked.
        EXPECT_EQ(row[1], std::to_string(raws[i].level)) << "raw LEVEL in datagram " << i;
        for (std::size_t t = 0; t < std::size(names); ++t) {
            // Every value differs from the one before: message i is datagram i's.
            const auto messages = recorder_->messages_on(topic(std::string("tank/") + names[t]));
            ASSERT_GT(messages.size(), i) << names[t];
            const auto published = json::parse(messages[i].payload);
            EXPECT_TRUE(agree(TagType::lreal, row[2 + t], published.at("value")))
                << names[t] << " in datagram " << i << ": tshark " << row[2 + t] << ", gateway "
                << published.dump();
        }
    }
}

TEST_F(DissectorEngineering, TsharkShowsEachElementOfAnArrayAndTheTextOfAString) {
    start(ExchangeYaml::consume("line", "10.1.2.3", 78)
              .length(24)
              .timeout_ms(0)
              .tag("TEMPS", "0.0", "real", "count: 3")
              .tag("BATCH", "12.0", "string", "length: 6")
              .tag("FLAGS", "18.6", "bit", "count: 3")
              .tag("LEVELS", "20.0", "int", "count: 2, scale: { raw: [0, 100], eu: [0, 10] }")
              .str());
    const auto now_s = static_cast<std::uint32_t>(std::time(nullptr));
    DatagramBuilder builder("10.1.2.3", 78, 24);
    builder.request_id(1).timestamp(now_s, 0);
    builder.set("0.0", TagType::real, Value{71.5f})
        .set("4.0", TagType::real, Value{-2.25f})
        .set("8.0", TagType::real, Value{0.0f})
        .set("20.0", TagType::int_, Value{std::int64_t{50}})
        .set("22.0", TagType::int_, Value{std::int64_t{100}});
    const std::string batch("Caf\xE9", 4);  // Latin-1, NUL-padded to 6
    for (std::size_t i = 0; i < batch.size(); ++i) {
        builder.data()[12 + i] = static_cast<std::byte>(batch[i]);
    }
    builder.data()[18] = std::byte{0x80};  // 18.7 set: the second element
    builder.data()[19] = std::byte{0x01};  // 19.0 set: the third
    const auto bytes = builder.build();
    send(bytes);
    const auto published =
        json::parse(expect_field(topic("line/BATCH"), "value", "\"Caf\xC3\xA9\"").payload);
    EXPECT_EQ(published["value"], "Caf\xC3\xA9");
    const std::string pcap_path = dir_.path() + "/line.pcap";
    PcapWriter pcap(pcap_path);
    pcap.add(bytes, std::uint64_t{now_s} * 1000000, udp_port_);
    ASSERT_TRUE(pcap.close());

    const auto decoded =
        tshark_fields(write_dissector(config_path_, dir_.path()), pcap_path,
                      {"eip2mqtt.line.TEMPS", "eip2mqtt.line.BATCH", "eip2mqtt.line.FLAGS",
                       "eip2mqtt.line.LEVELS", "eip2mqtt.line.LEVELS.eu"});
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), 1u) << decoded.output;
    const auto& row = decoded.rows[0];
    // Column 0 is the frame's; each occurrence of a field is one element, in order.
    EXPECT_EQ(row[1], "71.5,-2.25,0") << decoded.output;
    EXPECT_EQ(row[2], "Caf\xC3\xA9") << decoded.output;
    EXPECT_EQ(row[3], "0,1,1") << decoded.output;
    EXPECT_EQ(row[4], "50,100") << decoded.output;
    EXPECT_EQ(row[5], "5,10") << decoded.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
