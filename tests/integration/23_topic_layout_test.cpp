// Topics laid out by asset, end to end (docs/configuration.md, "Topics and payloads"): the real
// binary against a real Mosquitto and real UDP. A template puts each tag at its asset's path,
// two tags of one exchange at two assets; the exchange's own topics stay beside its topic;
// `_meta` names each tag's topic; a write on an asset path's `set` reaches the datagram.

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

const std::string by_asset = "  topic_template: \"{base}/{area}/{asset}/{tag}\"\n";

std::string turbine() {
    return ExchangeYaml::consume("turbine1", "10.0.0.1", 1)
        .length(8)
        .period_ms(100)
        .timeout_ms(60000)
        .key("location", "{ area: turbine-hall, asset: t1 }")
        .tag("SPEED", "0.0", "real")
        .tag("LUBE_P", "4.0", "real",
             "location: { asset: t1/lube-pump }, topic_name: pressure, unit: bar")
        .str();
}

std::vector<std::byte> turbine_datagram(std::uint16_t rid, float speed, float pressure) {
    DatagramBuilder builder("10.0.0.1", 1, 8);
    builder.request_id(rid);
    builder.set("0.0", TagType::real, Value{speed});
    builder.set("4.0", TagType::real, Value{pressure});
    return builder.build();
}

class TopicLayoutTest : public GatewayTest {};

TEST_F(TopicLayoutTest, TwoTagsOfOneExchangeArePublishedAtTwoAssetsPaths) {
    start(turbine(), by_asset);
    send(turbine_datagram(1, 3000.5f, 2.25f));
    expect_field(topic("turbine-hall/t1/SPEED"), "value", "3000.5");
    expect_field(topic("turbine-hall/t1/lube-pump/pressure"), "value", "2.25");
    // Nothing at the wire's shape, and the exchange's own topics where they were.
    EXPECT_TRUE(recorder_->messages_on(topic("turbine1/SPEED")).empty());
    EXPECT_TRUE(recorder_->wait_for_message(topic("turbine1/_status"), nullptr, 10s).has_value());
    const auto meta = recorder_->wait_for_message(topic("turbine1/_meta"), nullptr, 10s);
    ASSERT_TRUE(meta.has_value());
    const auto tags = json::parse(meta->payload)["tags"];
    EXPECT_EQ(tags["SPEED"]["topic"], topic("turbine-hall/t1/SPEED"));
    EXPECT_EQ(tags["LUBE_P"]["topic"], topic("turbine-hall/t1/lube-pump/pressure"));
}

TEST_F(TopicLayoutTest, ATagsOwnTopicOverridesTheTemplate) {
    start(ExchangeYaml::consume("turbine1", "10.0.0.1", 1)
              .length(8)
              .period_ms(100)
              .timeout_ms(60000)
              .tag("SPEED", "0.0", "real", "topic: test/elsewhere/speed")
              .tag("LUBE_P", "4.0", "real", "location: { area: \"\", asset: \"\" }")
              .str(),
          by_asset);
    send(turbine_datagram(1, 10.0f, 1.0f));
    expect_field(topic("elsewhere/speed"), "value", "10.0");
    // No area nor asset: both levels are left out, never empty.
    expect_field(topic("LUBE_P"), "value", "1.0");
}

TEST_F(TopicLayoutTest, AWriteOnAnAssetPathsSetReachesTheProducedDatagram) {
    UdpClient capture;
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture.port()))
              .period_ms(20)
              .key("location", "{ area: turbine-hall, asset: t1 }")
              .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 3000")
              .tag("VALVE_SP", "4.0", "dint",
                   "writable: true, location: { asset: t1/valve }, topic_name: setpoint")
              .str(),
          by_asset);
    ASSERT_TRUE(capture.receive(5s).has_value());
    EXPECT_EQ(write_result("turbine-hall/t1/valve/setpoint/set", "42"), R"({"ok":true})");
    const auto sent = capture.latest(5s);
    ASSERT_TRUE(sent.has_value() && sent->size() >= 32 + 8u);
    EXPECT_EQ(core::plan::decode_value(std::span(*sent).subspan(32), TagType::dint, {4, 0}),
              Value{std::int64_t{42}});
    expect_field(topic("turbine-hall/t1/valve/setpoint"), "value", "42");
    // The exchange's `set` stays under its topic and names tags as before.
    EXPECT_EQ(write_result("sp/set", R"({"SPEED_SP": 2500})"), R"({"ok":true})");
    expect_field(topic("turbine-hall/t1/SPEED_SP"), "value", "2500.0");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
