// Interop: a capture of the real `eip2mqtt sim`, read by tshark with the generated plugin,
// decodes every tag of every datagram as the gateway published it on MQTT for the same
// datagrams: the simulator's values, not values chosen by the test.

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/dissector_values.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;
using nlohmann::json;

struct SimTag {
    const char* name;
    const char* address;
    TagType type;
};

/// Every type, unaligned where it can be; two bits, which the simulator toggles out of phase.
constexpr SimTag sim_tags[] = {
    {"B0", "0.0", TagType::bit},     {"B5", "0.5", TagType::bit},    {"U8", "1.0", TagType::byte},
    {"I16", "3.0", TagType::int_},   {"U16", "5.0", TagType::word},  {"I32", "7.0", TagType::dint},
    {"U32", "11.0", TagType::udint}, {"F32", "15.0", TagType::real}, {"I64", "19.0", TagType::lint},
    {"F64", "27.0", TagType::lreal},
};
/// Enough for the bits to toggle twice (every 10 cycles).
constexpr std::size_t sim_datagrams = 24;

struct Captured {
    std::vector<std::byte> bytes;
    std::uint64_t at_us;  ///< when the test received it, microseconds since 1970 UTC
};

std::uint16_t request_id_of(const std::vector<std::byte>& datagram) {
    return static_cast<std::uint16_t>(std::to_integer<unsigned>(datagram.at(2)) |
                                      std::to_integer<unsigned>(datagram.at(3)) << 8);
}

std::uint64_t now_us() {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                          std::chrono::system_clock::now().time_since_epoch())
                                          .count());
}

class DissectorSimCapture : public GatewayTest {
protected:
    /// The first `count` datagrams `eip2mqtt sim` sends, on the gateway's configuration, to a
    /// socket of the test's (not to the gateway).
    std::vector<Captured> capture_sim(std::size_t count) {
        UdpClient capture;
        ChildProcess sim({gateway_binary(), "sim", "-c", config_path_, "--port",
                          std::to_string(capture.port()), "--commands-port", "0"});
        std::vector<Captured> captured;
        while (captured.size() < count) {
            auto bytes = capture.receive(10s);
            if (!bytes) {
                ADD_FAILURE() << "the simulator sent " << captured.size() << " datagrams, not "
                              << count << "\n"
                              << sim.output();
                break;
            }
            captured.push_back({std::move(*bytes), now_us()});
        }
        sim.signal(SIGTERM);
        EXPECT_EQ(sim.wait(10s), 0) << sim.output();
        return captured;
    }

    /// The value of each tag the gateway published for datagram `i`: the tags it changed are in
    /// the datagram's `_values` message; the others keep the value published before.
    static json published_for(const std::vector<Received>& batches, std::size_t i) {
        json values = json::object();
        for (std::size_t k = 0; k <= i; ++k) {
            values.update(json::parse(batches[k].payload).at("values"));
        }
        return values;
    }
};

TEST_F(DissectorSimCapture, TsharkDecodesEveryTagOfTheSimulatorAsTheGatewayPublishedIt) {
    auto yaml = ExchangeYaml::consume("sim", "10.0.0.9", 3).period_ms(20).timeout_ms(0);
    // No periodic refresh (refresh_s: 0), however slowly a loaded machine runs the test: one
    // `_values` message per datagram that changed a tag, and the simulator's byte ramps, so
    // every datagram does.
    for (const auto& tag : sim_tags) {
        yaml.tag(tag.name, tag.address, std::string(core::plan::to_string(tag.type)),
                 "refresh_s: 0");
    }
    start(yaml.str(), "  batch: true\n");
    const auto captured = capture_sim(sim_datagrams);
    ASSERT_EQ(captured.size(), sim_datagrams);

    const auto batches_topic = topic("sim/_values");
    const std::string pcap_path = dir_.path() + "/sim.pcap";
    PcapWriter pcap(pcap_path);
    for (std::size_t i = 0; i < captured.size(); ++i) {
        pcap.add(captured[i].bytes, captured[i].at_us, udp_port_);
        send(captured[i].bytes);
        ASSERT_TRUE(recorder_->wait_for([&](const std::vector<Received>& messages) {
            return static_cast<std::size_t>(std::count_if(
                       messages.begin(), messages.end(),
                       [&](const Received& m) { return m.topic == batches_topic; })) > i;
        })) << "datagram "
            << i;
    }
    ASSERT_TRUE(pcap.close());
    const auto batches = recorder_->messages_on(batches_topic);
    ASSERT_EQ(batches.size(), sim_datagrams);

    std::vector<std::string> fields{"eip2mqtt.request_id"};
    for (const auto& tag : sim_tags) fields.push_back(std::string("eip2mqtt.sim.") + tag.name);
    const auto decoded =
        tshark_fields(write_dissector(config_path_, dir_.path()), pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), sim_datagrams) << decoded.output;
    for (std::size_t i = 0; i < sim_datagrams; ++i) {
        const auto& row = decoded.rows[i];
        EXPECT_EQ(row[1], std::to_string(request_id_of(captured[i].bytes))) << "datagram " << i;
        const auto published = published_for(batches, i);
        for (std::size_t t = 0; t < std::size(sim_tags); ++t) {
            ASSERT_TRUE(published.contains(sim_tags[t].name)) << sim_tags[t].name;
            EXPECT_TRUE(agree(sim_tags[t].type, row[2 + t], published.at(sim_tags[t].name)))
                << sim_tags[t].name << " in datagram " << i;
        }
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
