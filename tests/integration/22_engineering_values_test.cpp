// Engineering values end to end, the real binary against a real Mosquitto and real UDP: raw
// values on the wire published in units (linear with clamp, square root, gain and offset), a
// percent deadband, writes in units carried as raw bytes, and Sparkplug births read by Eclipse
// Tahu carrying the units and the range.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/published_value.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

const std::string level_keys =
    "unit: '%', scale: { raw: [0, 32000], eu: [0, 100], clamp: true }, "
    "deadband: { percent: 0.5 }, publish_raw: true";
const std::string oil_keys = "unit: degC, scale: { gain: 0.1, offset: -40 }";

std::string tank_exchange() {
    return ExchangeYaml::consume("tank", "10.0.0.1", 1)
        .length(10)
        .period_ms(100)
        .timeout_ms(60000)
        .tag("LEVEL", "0.0", "int", level_keys)
        .tag("FLOW", "2.0", "word", "scale: { raw: [0, 65535], eu: [0, 500], sqrt: true }")
        .tag("OIL", "4.0", "dint", oil_keys)
        .tag("MARKER", "8.0", "word")
        .str();
}

std::vector<std::byte> tank(std::uint16_t rid, std::int64_t level, std::uint64_t flow,
                            std::int64_t oil) {
    return DatagramBuilder("10.0.0.1", 1, 10)
        .request_id(rid)
        .set("0.0", TagType::int_, Value{level})
        .set("2.0", TagType::word, Value{flow})
        .set("4.0", TagType::dint, Value{oil})
        .set("8.0", TagType::word, Value{std::uint64_t{rid}})
        .build();
}

class EngineeringValuesTest : public GatewayTest {
protected:
    /// Sends datagram `rid` and waits until its MARKER is out: the datagram was handled whole.
    void send_tank(std::uint16_t rid, std::int64_t level, std::uint64_t flow, std::int64_t oil) {
        send(tank(rid, level, flow, oil));
        expect_field(topic("tank/MARKER"), "value", std::to_string(rid));
    }

    std::vector<json> payloads_on(const std::string& suffix) {
        std::vector<json> out;
        for (const auto& m : recorder_->messages_on(topic(suffix))) {
            out.push_back(json::parse(m.payload));
        }
        return out;
    }
};

TEST_F(EngineeringValuesTest, RawValuesArePublishedInUnits) {
    start(tank_exchange());
    send_tank(1, 8000, 16384, 650);
    const auto level = json::parse(expect_field(topic("tank/LEVEL"), "value", "25.0").payload);
    EXPECT_EQ(level["raw"], 8000);
    EXPECT_FALSE(level.contains("limit"));
    const auto flow = json::parse(recorder_->messages_on(topic("tank/FLOW")).back().payload);
    EXPECT_NEAR(flow["value"].get<double>(), 250.0, 0.01);  // 500 x sqrt(16384 / 65535)
    EXPECT_FALSE(flow.contains("raw"));
    expect_field(topic("tank/OIL"), "value", "25.0");  // 650 x 0.1 - 40

    // Beyond the raw range: held at the end with clamp, flagged either way.
    send_tank(2, 32767, 0, 650);
    const auto high = json::parse(expect_field(topic("tank/LEVEL"), "value", "100.0").payload);
    EXPECT_EQ(high["limit"], "high");
    EXPECT_EQ(high["raw"], 32767);
    expect_field(topic("tank/FLOW"), "value", "0.0");
    // Counted: one publication beyond the raw range, in the exchange's status.
    expect_field(topic("tank/_status"), "beyond_raw_range", "1");
}

TEST_F(EngineeringValuesTest, APercentDeadbandIsOfTheSpan) {
    start(tank_exchange());
    // Raw values of 125 x k read exactly k / 2.56 %: the comparisons are of exact doubles.
    send_tank(1, 8000, 0, 0);  // 25.0
    send_tank(2, 8125, 0, 0);  // 25.390625: within 0.5 % of 100
    send_tank(3, 8250, 0, 0);  // 25.78125: beyond it
    send_tank(4, 8375, 0, 0);  // 26.171875: within it of 25.78125
    std::vector<double> levels;
    for (const auto& p : payloads_on("tank/LEVEL")) levels.push_back(p["value"].get<double>());
    EXPECT_EQ(levels, (std::vector<double>{25.0, 25.78125}));
}

TEST_F(EngineeringValuesTest, AReloadedScaleAppliesToTheNextPublication) {
    start(tank_exchange());
    send_tank(1, 8000, 0, 650);
    expect_field(topic("tank/LEVEL"), "value", "25.0");
    auto rescaled = tank_exchange();
    const std::string from = "eu: [0, 100]";
    rescaled.replace(rescaled.find(from), from.size(), "eu: [0, 200]");
    rewrite_exchanges(rescaled);
    const auto meta_from = recorder_->count();
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    // `_meta` says the new range, and the same raw value now reads twice as much.
    const auto meta = recorder_->wait_for_message(
        topic("tank/_meta"),
        [](const std::string& p) {
            return !p.empty() && json::parse(p)["tags"]["LEVEL"]["scale"]["eu"][1] == 200.0;
        },
        10s, meta_from);
    EXPECT_TRUE(meta.has_value());
    send_tank(2, 8000, 0, 650);
    expect_field(topic("tank/LEVEL"), "value", "50.0");
}

class EngineeringWritesTest : public GatewayTest {
protected:
    void SetUp() override {
        capture_ = std::make_unique<UdpClient>();
        start(ExchangeYaml::produce("sp", "10.1.2.3", 10,
                                    "127.0.0.1:" + std::to_string(capture_->port()))
                  .period_ms(20)
                  .tag("OIL_SP", "0.0", "dint",
                       oil_keys + ", writable: true, min: -40, max: 150, initial: 20")
                  .tag("LEVEL_SP", "4.0", "int",
                       "scale: { raw: [0, 32000], eu: [0, 100] }, writable: true")
                  .str());
        ASSERT_TRUE(capture_->receive(5s).has_value());
    }

    json write(const std::string& tag, const std::string& payload) {
        const auto result = write_result("sp/" + tag + "/set", payload);
        return result.empty() ? json() : json::parse(result);
    }

    /// The gateway's current image (a write's result follows its datagram).
    std::vector<std::byte> last_sent() {
        auto last = capture_->latest(5s);
        EXPECT_TRUE(last.has_value());
        return last.value_or(std::vector<std::byte>{});
    }

    Value raw_at(const std::vector<std::byte>& bytes, std::uint16_t byte, TagType type) {
        if (bytes.size() < 32 + 6u) return Value{false};
        return core::plan::decode_value(std::span(bytes).subspan(32), type, {byte, 0});
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(EngineeringWritesTest, AWriteInUnitsIsCarriedRawAndEchoedAsItReadsBack) {
    // `initial: 20` in degC: raw 600.
    EXPECT_EQ(raw_at(last_sent(), 0, TagType::dint), Value{std::int64_t{600}});
    EXPECT_EQ(write("OIL_SP", "25.2"), json({{"ok", true}}));
    EXPECT_EQ(raw_at(last_sent(), 0, TagType::dint), Value{std::int64_t{652}});
    // The echo is what raw 652 reads as, computed as the gateway does, not the 25.2 asked.
    core::plan::TagSpec spec;
    spec.type = TagType::dint;
    spec.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::gain_offset, {}, {}, 0.1, -40, false, std::nullopt};
    const auto echoed =
        core::plan::to_json(core::plan::published_value(spec, Value{std::int64_t{652}}).value);
    expect_field(topic("sp/OIL_SP"), "value", echoed);

    EXPECT_EQ(write("LEVEL_SP", "50"), json({{"ok", true}}));
    EXPECT_EQ(raw_at(last_sent(), 4, TagType::int_), Value{std::int64_t{16000}});
}

TEST_F(EngineeringWritesTest, WritesBeyondTheLimitsOrTheRawTypeAreRefused) {
    const auto above = write("OIL_SP", "150.5");
    EXPECT_EQ(above["ok"], false);
    EXPECT_EQ(above["error"], "above max 150");
    const auto raw = write("LEVEL_SP", "103");  // raw 32960: no int holds it
    EXPECT_EQ(raw["ok"], false);
    EXPECT_EQ(raw["error"], "raw value out of range for int (-32768..32767)");
    EXPECT_EQ(raw_at(last_sent(), 0, TagType::dint), Value{std::int64_t{600}});
}

TEST_F(EngineeringValuesTest, SparkplugBirthsCarryUnitsAndTheRangeAsDoubles) {
    GatewayOptions options;
    options.sections = "sparkplug:\n  group_id: plant1\n";
    start(tank_exchange(), "", options);
    send(tank(1, 8000, 0, 650));
    const auto birth =
        recorder_->wait_for_message("spBv1.0/plant1/DBIRTH/test-gw/tank", nullptr, 10s);
    ASSERT_TRUE(birth.has_value());
    const auto decoded = tahu_decode(birth->payload);
    json level;
    json oil;
    for (const auto& m : decoded["metrics"]) {
        if (m["name"] == "LEVEL") level = m;
        if (m["name"] == "OIL") oil = m;
    }
    EXPECT_EQ(level["type"], "Double");
    EXPECT_EQ(level["value"], 25.0);
    EXPECT_EQ(level["properties"]["engUnit"]["value"], "%");
    EXPECT_EQ(level["properties"]["engLow"]["value"], 0);
    EXPECT_EQ(level["properties"]["engHigh"]["value"], 100);
    EXPECT_EQ(level["properties"]["engHigh"]["type"], "Double");
    EXPECT_EQ(oil["type"], "Double");
    EXPECT_EQ(oil["value"], 25.0);
    EXPECT_FALSE(oil["properties"].contains("engLow"));  // gain and offset have no range
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
