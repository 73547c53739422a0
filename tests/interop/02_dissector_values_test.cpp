// Interop: the Wireshark plugin `eip2mqtt dissector` generates decodes, in tshark, the same value
// of every tag that the gateway publishes on MQTT for the same datagrams: two decoders, one in
// C++ and one generated in Lua, agreeing value by value.

#include <algorithm>
#include <ctime>
#include <limits>
#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/dissector_values.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/pcap_writer.hpp"
#include "tests/support/tshark.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;
using nlohmann::json;

struct TagCase {
    const char* name;
    const char* address;
    TagType type;
};

/// Every type, unaligned where it can be.
constexpr TagCase tags[] = {
    {"SPEED", "0.0", TagType::real},   {"TRIP", "4.6", TagType::bit},
    {"LEVEL", "5.0", TagType::byte},   {"DELTA", "6.0", TagType::int_},
    {"COUNT", "8.0", TagType::word},   {"POSITION", "10.0", TagType::dint},
    {"TOTAL", "14.0", TagType::udint}, {"ENERGY", "18.0", TagType::lint},
    {"RATIO", "26.0", TagType::lreal},
};
constexpr std::size_t length = 40;
constexpr int datagrams = 12;

/// The value of tag `t` in datagram `i`: each differs from the one before (every datagram is
/// published whole), extremes and values with every significant digit among them.
core::plan::Value value_of(std::size_t t, int i) {
    const bool odd = i % 2 == 1;
    switch (tags[t].type) {
        case TagType::real:
            if (i == 3) return std::numeric_limits<float>::max();
            if (i == 5) return std::numeric_limits<float>::min();
            return static_cast<float>((odd ? -1 : 1) * (1234.5678 + i * 0.37));
        case TagType::bit:
            return odd;
        case TagType::byte:
            return std::uint64_t(odd ? 255 - i : i);
        case TagType::int_:
            return std::int64_t(odd ? -32768 + i : 32767 - i);
        case TagType::word:
            return std::uint64_t(odd ? 65535 - i : i * 1000);
        case TagType::dint:
            return std::int64_t(odd ? -2147483647 - 1 + i : 2147483647 - i);
        case TagType::udint:
            return std::uint64_t(odd ? 4294967295u - i : 123456789u * i);
        case TagType::lint:
            return odd ? std::numeric_limits<std::int64_t>::min() + i
                       : std::numeric_limits<std::int64_t>::max() - i;
        case TagType::lreal:
            if (i == 4) return std::numeric_limits<double>::max();
            if (i == 6) return std::numeric_limits<double>::denorm_min();
            return (odd ? -1.0 : 1.0) * (i + 1) / 3.0;
        case TagType::string:  // none here: the engineering test has one
            break;
    }
    return false;
}

std::vector<std::byte> datagram(int i, std::uint32_t time_s) {
    DatagramBuilder builder("10.1.2.3", 77, length);
    builder.request_id(static_cast<std::uint16_t>(100 + i)).timestamp(time_s, 0);
    for (std::size_t t = 0; t < std::size(tags); ++t) {
        builder.set(tags[t].address, tags[t].type, value_of(t, i));
    }
    return builder.build();
}

class DissectorValues : public GatewayTest {
protected:
    /// How many datagrams every tag has been published for.
    std::size_t published_datagrams(const std::vector<Received>& messages) const {
        std::size_t fewest = std::numeric_limits<std::size_t>::max();
        for (const auto& tag : tags) {
            const auto tag_topic = topic(std::string("plant/") + tag.name);
            fewest = std::min<std::size_t>(
                fewest, std::count_if(messages.begin(), messages.end(),
                                      [&](const Received& m) { return m.topic == tag_topic; }));
        }
        return fewest;
    }

    /// `eip2mqtt dissector` on the running gateway's configuration.
    std::string write_plugin() { return write_dissector(config_path_, dir_.path()); }
};

TEST_F(DissectorValues, TsharkDecodesEveryTagAsTheGatewayPublishedIt) {
    auto yaml = ExchangeYaml::consume("plant", "10.1.2.3", 77).length(length).timeout_ms(0);
    for (const auto& tag : tags) {
        yaml.tag(tag.name, tag.address, std::string(core::plan::to_string(tag.type)),
                 tag.type == TagType::real ? "unit: rpm" : "");
    }
    start(yaml.str());
    const std::uint32_t now_s = static_cast<std::uint32_t>(std::time(nullptr));
    const std::string pcap_path = dir_.path() + "/plant.pcap";
    PcapWriter pcap(pcap_path);
    for (int i = 0; i < datagrams; ++i) {
        const auto bytes = datagram(i, now_s);
        send(bytes);
        pcap.add(bytes, (std::uint64_t{now_s} * 1000 + i) * 1000, udp_port_);
        // Each datagram changes every tag: wait for all of its publications before the next.
        ASSERT_TRUE(recorder_->wait_for([&](const std::vector<Received>& messages) {
            return published_datagrams(messages) > static_cast<std::size_t>(i);
        })) << "datagram "
            << i;
    }
    ASSERT_TRUE(pcap.close());

    std::vector<std::string> fields{"eip2mqtt.request_id"};
    for (const auto& tag : tags) fields.push_back(std::string("eip2mqtt.plant.") + tag.name);
    const auto decoded = tshark_fields(write_plugin(), pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), static_cast<std::size_t>(datagrams)) << decoded.output;
    for (int i = 0; i < datagrams; ++i) {
        const auto& row = decoded.rows[i];
        EXPECT_EQ(row[1], std::to_string(100 + i));
        for (std::size_t t = 0; t < std::size(tags); ++t) {
            const auto messages =
                recorder_->messages_on(topic(std::string("plant/") + tags[t].name));
            const auto published = json::parse(messages[i].payload).at("value");
            EXPECT_TRUE(agree(tags[t].type, row[2 + t], published))
                << tags[t].name << " in datagram " << i;
        }
    }
}

TEST_F(DissectorValues, TsharkDecodesTheGatewaysOwnProducedDatagramAsItPublishedIt) {
    // Initial values, as YAML writes them, of each tag of `tags` in order.
    const char* const initial[] = {"1234.5678", "true",        "200",        "-1234",
                                   "65000",     "-2000000000", "4000000000", "-9000000000000000000",
                                   "0.1"};
    UdpClient capture;
    auto yaml =
        ExchangeYaml::produce("out", "10.1.2.4", 78, "127.0.0.1:" + std::to_string(capture.port()))
            .length(length)
            .period_ms(50);
    for (std::size_t t = 0; t < std::size(tags); ++t) {
        yaml.tag(tags[t].name, tags[t].address, std::string(core::plan::to_string(tags[t].type)),
                 std::string("initial: ") + initial[t]);
    }
    start(yaml.str());
    const auto bytes = capture.receive(5s);
    ASSERT_TRUE(bytes.has_value());
    // The echo of the produced values, published at start.
    ASSERT_TRUE(recorder_->wait_for([&](const std::vector<Received>& messages) {
        for (const auto& tag : tags) {
            const auto tag_topic = topic(std::string("out/") + tag.name);
            if (std::none_of(messages.begin(), messages.end(),
                             [&](const Received& m) { return m.topic == tag_topic; })) {
                return false;
            }
        }
        return true;
    }));

    const std::string pcap_path = dir_.path() + "/produced.pcap";
    PcapWriter pcap(pcap_path);
    pcap.add(*bytes, std::uint64_t{1700000000} * 1000000, udp_port_);
    ASSERT_TRUE(pcap.close());
    std::vector<std::string> fields;
    for (const auto& tag : tags) fields.push_back(std::string("eip2mqtt.out.") + tag.name);
    const auto decoded = tshark_fields(write_plugin(), pcap_path, fields);
    ASSERT_EQ(decoded.status, 0) << decoded.output;
    ASSERT_EQ(decoded.rows.size(), 1u) << decoded.output;
    for (std::size_t t = 0; t < std::size(tags); ++t) {
        const auto published =
            json::parse(recorder_->last(topic(std::string("out/") + tags[t].name))->payload)
                .at("value");
        EXPECT_TRUE(agree(tags[t].type, decoded.rows[0][1 + t], published)) << tags[t].name;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
