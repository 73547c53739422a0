// Sparkplug births against a broker's Maximum Packet Size (a real Mosquitto with
// `max_packet_size`): a DBIRTH over it is never published, its device is not born and sends no
// DDATA, and seq counts only what was published, read by Eclipse Tahu's decoder. `check`
// estimates each birth and warns of one over `sparkplug.max_packet_bytes`, and refuses names
// that make a Sparkplug topic longer than MQTT allows.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr std::size_t big_tags = 400;

std::string topic_of(const std::string& type, const std::string& device = "") {
    return "spBv1.0/plant1/" + type + "/test-gw" + (device.empty() ? "" : "/" + device);
}

/// 400 ints with a unit and a description: a DBIRTH of some 40 kB.
std::string big_exchange() {
    // Never stale in the test: a device that is not up is not born either.
    auto big = ExchangeYaml::consume("big", "10.9.9.9", 1)
                   .length(2 * big_tags)
                   .period_ms(100)
                   .timeout_ms(60000);
    for (std::size_t i = 0; i < big_tags; ++i) {
        big.tag("BOILER_FEED_PRESSURE_" + std::to_string(i), std::to_string(2 * i) + ".0", "int",
                "unit: kPa, description: feed pressure of a boiler");
    }
    return big.str();
}

std::string small_exchange() {
    return ExchangeYaml::consume("small", "10.9.9.9", 2)
        .length(4)
        .period_ms(100)
        .timeout_ms(60000)
        .tag("PV", "0.0", "int")
        .tag("SV", "2.0", "int")
        .str();
}

class SparkplugPacketSizeTest : public GatewayTest {
protected:
    void send_both(std::uint16_t request_id, std::int64_t value) {
        DatagramBuilder big("10.9.9.9", 1, 2 * big_tags);
        big.request_id(request_id);
        for (std::size_t i = 0; i < big_tags; ++i) {
            big.set(std::to_string(2 * i) + ".0", TagType::int_, Value{value});
        }
        send(big.build());
        send(DatagramBuilder("10.9.9.9", 2, 4)
                 .request_id(request_id)
                 .set("0.0", TagType::int_, Value{value})
                 .build());
    }
    /// The index just after the next message on `topic` from `from`; fails the test without one.
    std::size_t after_next(const std::string& topic, std::size_t from) {
        std::size_t found = 0;
        const bool seen = recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                for (std::size_t i = from; i < all.size(); ++i) {
                    if (all[i].topic == topic) {
                        found = i + 1;
                        return true;
                    }
                }
                return false;
            },
            20s);
        EXPECT_TRUE(seen) << "nothing on " << topic;
        return found;
    }
};

TEST_F(SparkplugPacketSizeTest, ADbirthOverTheBrokersLimitLeavesItsDeviceUnbornAndSeqWhole) {
    GatewayOptions options;
    options.broker.extra_config = "max_packet_size 20000\n";
    options.sections = "sparkplug:\n  group_id: plant1\n";
    start(big_exchange() + small_exchange(), "", options);
    after_next(topic_of("NBIRTH"), 0);
    send_both(1, 5);
    auto from = after_next(topic_of("DBIRTH", "small"), 0);
    // Values change in both: DDATA of the small device only.
    send_both(2, 6);
    from = after_next(topic_of("DDATA", "small"), from);
    // A host's rebirth request: the node and the small device again, the big one refused again.
    recorder_->publish(topic_of("NCMD"),
                       tahu_encode({{"timestamp", 1700000000000},
                                    {"metrics", json::array({{{"name", "Node Control/Rebirth"},
                                                              {"type", "Boolean"},
                                                              {"value", true}}})}}));
    from = after_next(topic_of("NBIRTH"), from);
    from = after_next(topic_of("DBIRTH", "small"), from);
    send_both(3, 7);
    after_next(topic_of("DDATA", "small"), from);
    // Counted: the refusals in the metrics topic.
    const auto metrics = recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& payload) {
            const auto m = json::parse(payload, nullptr, false);
            return m.is_object() && m.contains("sparkplug") &&
                   m["sparkplug"].value("births_refused", 0) >= 2;
        },
        15s, 0);
    ASSERT_TRUE(metrics.has_value());
    // The documented metrics schema has the `sparkplug` object, and `offline` in the refusals.
    EXPECT_EQ(schema_problem(schema_file("metrics.json"), metrics->payload), "");
    EXPECT_TRUE(recorder_->messages_on(topic_of("DBIRTH", "big")).empty());
    EXPECT_TRUE(recorder_->messages_on(topic_of("DDATA", "big")).empty());

    // seq counts every message of the node, from each NBIRTH's 0, with no gap.
    std::vector<std::string> topics, payloads;
    for (const auto& m : recorder_->messages()) {
        if (!m.topic.starts_with("spBv1.0/plant1/") || m.topic == topic_of("NDEATH") ||
            m.topic == topic_of("NCMD")) {
            continue;
        }
        topics.push_back(m.topic);
        payloads.push_back(m.payload);
    }
    const auto decoded = tahu_decode_all(payloads);
    ASSERT_EQ(decoded.size(), topics.size());
    int expected = 0;
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        if (topics[i] == topic_of("NBIRTH")) expected = 0;
        ASSERT_TRUE(decoded[i].contains("seq")) << topics[i];
        EXPECT_EQ(decoded[i]["seq"], std::to_string(expected++)) << i << ": " << topics[i];
    }
    EXPECT_GE(decoded.size(), 6u);
    EXPECT_NE(gateway_->output().find("spBv1.0/plant1/DBIRTH/test-gw/big not published"),
              std::string::npos)
        << gateway_->output();
}

TEST_F(SparkplugPacketSizeTest, CheckEstimatesEachBirthAndWarnsOfOneOverMaxPacketBytes) {
    const auto config = dir_.write("check.yaml",
                                   "gateway:\n  id: gw\nsparkplug:\n  group_id: plant1\n"
                                   "  max_packet_bytes: 20000\nexchanges:\n" +
                                       big_exchange() + small_exchange());
    const auto result = run_command({gateway_binary(), "check", "-c", config}, 60s);
    EXPECT_EQ(result.status, 0) << result.output;
    EXPECT_NE(result.output.find("sparkplug NBIRTH: at most "), std::string::npos);
    EXPECT_NE(result.output.find("warning: the Sparkplug DBIRTH may take "), std::string::npos)
        << result.output;
    // One warning, for the big exchange: it comes before the small one's listing.
    const auto warning = result.output.find("warning: the Sparkplug DBIRTH");
    EXPECT_EQ(result.output.find("warning: the Sparkplug DBIRTH", warning + 1), std::string::npos);
    EXPECT_LT(warning, result.output.find("exchange small:"));
    EXPECT_NE(result.output.find("over sparkplug.max_packet_bytes (20000)"), std::string::npos);
}

TEST_F(SparkplugPacketSizeTest, CheckRefusesAnExchangeNameThatMakesASparkplugTopicTooLong) {
    // 70,000 bytes: its JSON topic is short (`topic:`), its device topic is not.
    const std::string name(70000, 'x');
    const auto config =
        dir_.write("long.yaml", "gateway:\n  id: gw\nsparkplug:\n  group_id: plant1\nexchanges:\n" +
                                    ExchangeYaml::consume(name, "10.9.9.9", 1)
                                        .length(2)
                                        .topic("short")
                                        .tag("PV", "0.0", "int")
                                        .str());
    const auto result = run_command({gateway_binary(), "check", "-c", config}, 60s);
    EXPECT_EQ(result.status, 1) << result.output.substr(0, 2000);
    EXPECT_NE(result.output.find("makes topic 'spBv1.0/{group_id}/DBIRTH/{edge_node_id}/"
                                 "{exchange}' 70025 bytes long (MQTT allows 65535)"),
              std::string::npos)
        << result.output.substr(0, 2000);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
