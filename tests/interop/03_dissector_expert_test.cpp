// Interop: the generated Wireshark plugin raises one expert entry per rule of the gateway (a
// signature or length against the configuration, request-id gaps, duplicates and steps back,
// status, the producer clock, exchanges nobody configured), on exactly the frames that break it.

#include <cstdint>
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

const char* const config_text =
    "gateway:\n"
    "  id: expert-test\n"
    "mqtt:\n"
    "  url: tcp://127.0.0.1:1883\n"
    "  base_topic: test\n"
    "exchanges:\n"
    "  - name: pump\n"
    "    producer_id: 10.0.0.9\n"
    "    exchange_id: 5\n"
    "    length: 8\n"
    "    signature: \"2.5\"\n"
    "    timeout_ms: 0\n"
    "    clock_tolerance_ms: 2000\n"
    "    tags:\n"
    "      - { name: FLOW, address: \"0.0\", type: word }\n";

struct Frame {
    std::vector<std::byte> bytes;
    std::uint64_t at_ms;  ///< capture time
};

/// A datagram of `pump`, stamped by a synchronised producer at `at_ms`, signature 2.5.
DatagramBuilder pump(std::uint16_t request_id, std::uint64_t at_ms, std::size_t length = 8) {
    DatagramBuilder builder("10.0.0.9", 5, length);
    builder.request_id(request_id)
        .timestamp(static_cast<std::uint32_t>(at_ms / 1000),
                   static_cast<std::uint32_t>(at_ms % 1000 * 1000000))
        .signature(2, 5);
    return builder;
}

class DissectorExpert : public ::testing::Test {
protected:
    void SetUp() override {
        const auto config = dir_.write("expert.yaml", config_text);
        plugin_ = dir_.path() + "/eip2mqtt.lua";
        const auto result =
            run_command({gateway_binary(), "dissector", "-c", config, "-o", plugin_}, 30s);
        ASSERT_EQ(result.status, 0) << result.output;
    }

    /// The expert messages tshark shows for each frame ("" for none), in capture order.
    std::vector<std::string> experts(const std::vector<Frame>& frames) {
        const auto pcap_path = dir_.path() + "/frames.pcap";
        PcapWriter pcap(pcap_path);
        for (const auto& frame : frames) pcap.add(frame.bytes, frame.at_ms * 1000);
        EXPECT_TRUE(pcap.close());
        const auto decoded = tshark_fields(plugin_, pcap_path, {"_ws.expert.message"});
        EXPECT_EQ(decoded.status, 0) << decoded.output;
        EXPECT_EQ(decoded.rows.size(), frames.size()) << decoded.output;
        std::vector<std::string> messages;
        for (const auto& row : decoded.rows) messages.push_back(row[1]);
        return messages;
    }

    TempDir dir_;
    std::string plugin_;
};

TEST_F(DissectorExpert, SequenceGapDuplicateStepBackAndRestart) {
    std::vector<Frame> frames;
    const std::uint16_t ids[] = {10, 11, 14, 14, 12, 15};
    for (std::size_t i = 0; i < std::size(ids); ++i) {
        const auto at = t0_ms + i * 100;
        // The step back carries an older timestamp: late, not a restart.
        const auto stamped = ids[i] == 12 ? at - 1000 : at;
        frames.push_back({pump(ids[i], stamped).build(), at});
    }
    // Far behind, but stamped later: the producer restarted.
    frames.push_back({pump(3, t0_ms + 600).build(), t0_ms + 600});
    EXPECT_EQ(
        experts(frames),
        (std::vector<std::string>{"", "", "2 request ids missed between 11 and 14",
                                  "Duplicate request id 14", "Request id 12 steps back from 14", "",
                                  "Producer restarted: request id 3 after 15, with a later "
                                  "timestamp"}));
}

TEST_F(DissectorExpert, SignatureAndLengthAgainstTheConfiguration) {
    std::vector<Frame> frames;
    frames.push_back({pump(1, t0_ms).build(), t0_ms});
    frames.push_back({pump(2, t0_ms + 100).signature(3, 5).build(), t0_ms + 100});
    frames.push_back({pump(3, t0_ms + 200).signature(2, 4).build(), t0_ms + 200});
    // A newer minor may append data: longer is accepted.
    frames.push_back({pump(4, t0_ms + 300, 12).signature(2, 6).build(), t0_ms + 300});
    frames.push_back({pump(5, t0_ms + 400, 6).build(), t0_ms + 400});
    frames.push_back({pump(6, t0_ms + 500, 12).build(), t0_ms + 500});
    EXPECT_EQ(experts(frames),
              (std::vector<std::string>{
                  "", "Signature 3.5, configured 2.5", "Signature 2.4, configured 2.5", "",
                  "6 data bytes, configured 8", "12 data bytes, configured 8"}));
}

TEST_F(DissectorExpert, StatusNotZero) {
    auto builder = pump(1, t0_ms);
    builder.header().status = 7;
    EXPECT_EQ(experts({{pump(0, t0_ms).build(), t0_ms}, {builder.build(), t0_ms}}),
              (std::vector<std::string>{"", "Status 7"}));
}

TEST_F(DissectorExpert, ProducerClockBeyondTheTolerance) {
    const auto at = t0_ms + 10000;
    EXPECT_EQ(experts({{pump(1, at - 1500).build(), at},
                       {pump(2, at + 3600000).build(), at + 100},
                       {pump(3, at - 2500).build(), at + 200}}),
              (std::vector<std::string>{
                  "",
                  "Producer clock 3599900 ms ahead of the capture's, beyond clock_tolerance_ms "
                  "2000",
                  "Producer clock 2700 ms behind the capture's, beyond clock_tolerance_ms 2000"}));
}

TEST_F(DissectorExpert, AnExchangeNobodyConfigured) {
    DatagramBuilder stranger("10.0.0.9", 99, 4);
    stranger.request_id(1);
    EXPECT_EQ(experts({{pump(1, t0_ms).build(), t0_ms}, {stranger.build(), t0_ms}}),
              (std::vector<std::string>{
                  "", "No configured exchange has producer id 10.0.0.9 and exchange id 99"}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
