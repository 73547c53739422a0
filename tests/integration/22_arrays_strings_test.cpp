// Arrays and strings end to end, the real binary against a real Mosquitto and real UDP: an
// array of reals and of bits and a Latin-1 string published as JSON, a deadband per element,
// writes of a whole array, of one element and of a text carried as bytes on the wire, and the
// Sparkplug births of both.

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "sparkplug_b.pb.h"
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

std::string plant_exchange() {
    return ExchangeYaml::consume("plant", "10.0.0.1", 1)
        .length(32)
        .period_ms(100)
        .timeout_ms(60000)
        .tag("TEMPS", "0.0", "real", "count: 4, unit: degC, deadband: 0.5")
        .tag("BATCH", "16.0", "string", "length: 8")
        .tag("FLAGS", "24.6", "bit", "count: 4")
        .tag("MARKER", "30.0", "word")
        .str();
}

std::vector<std::byte> plant(std::uint16_t rid, std::array<float, 4> temps,
                             const std::string& batch, std::uint8_t flags) {
    DatagramBuilder builder("10.0.0.1", 1, 32);
    builder.request_id(rid);
    for (std::size_t i = 0; i < temps.size(); ++i) {
        builder.set(std::to_string(4 * i) + ".0", TagType::real, Value{temps[i]});
    }
    for (std::size_t i = 0; i < batch.size() && i < 8; ++i) {
        builder.data()[16 + i] = static_cast<std::byte>(batch[i]);
    }
    builder.data()[24] = static_cast<std::byte>(flags << 6);  // bits 0..1 of the first four
    builder.data()[25] = static_cast<std::byte>(flags >> 2);
    builder.set("30.0", TagType::word, Value{std::uint64_t{rid}});
    return builder.build();
}

class ArraysStringsTest : public GatewayTest {
protected:
    /// Sends datagram `rid` and waits until its MARKER is out: the datagram was handled whole.
    void send_plant(std::uint16_t rid, std::array<float, 4> temps, const std::string& batch,
                    std::uint8_t flags) {
        send(plant(rid, temps, batch, flags));
        expect_field(topic("plant/MARKER"), "value", std::to_string(rid));
    }

    std::vector<std::string> values_on(const std::string& suffix) {
        std::vector<std::string> out;
        for (const auto& m : recorder_->messages_on(topic(suffix))) {
            out.push_back(json::parse(m.payload)["value"].dump());
        }
        return out;
    }
};

TEST_F(ArraysStringsTest, ArraysAndStringsArePublishedAsJson) {
    start(plant_exchange());
    // "Café" in Latin-1, NUL-padded: published as UTF-8 without its padding.
    send_plant(1, {71.5f, 70.25f, 69.0f, 72.0f}, std::string("Caf\xE9", 4), 0b1011);
    expect_field(topic("plant/TEMPS"), "value", "[71.5,70.25,69.0,72.0]");
    expect_field(topic("plant/BATCH"), "value", "\"Caf\xC3\xA9\"");
    expect_field(topic("plant/FLAGS"), "value", "[true,true,false,true]");
    const auto meta = recorder_->wait_for_message(topic("plant/_meta"), nullptr, 10s);
    ASSERT_TRUE(meta.has_value());
    const auto tags = json::parse(meta->payload)["tags"];
    EXPECT_EQ(tags["TEMPS"]["count"], 4);
    EXPECT_EQ(tags["BATCH"]["type"], "string");
    EXPECT_EQ(tags["BATCH"]["length"], 8);
}

TEST_F(ArraysStringsTest, BatchModeCarriesTheArrayAndTheTextInValues) {
    start(plant_exchange(), "  batch: true\n");
    send(plant(1, {71.5f, 70.25f, 69.0f, 72.0f}, "B-1", 0b0001));
    const auto batch = recorder_->wait_for_message(
        topic("plant/_values"),
        [](const std::string& p) { return json::parse(p)["values"].contains("TEMPS"); }, 10s);
    ASSERT_TRUE(batch.has_value());
    const auto values = json::parse(batch->payload)["values"];
    EXPECT_EQ(values["TEMPS"].dump(), "[71.5,70.25,69.0,72.0]");
    EXPECT_EQ(values["BATCH"], "B-1");
    EXPECT_EQ(values["FLAGS"].dump(), "[true,false,false,false]");
}

TEST_F(ArraysStringsTest, OneElementBeyondTheDeadbandPublishesTheWholeArray) {
    start(plant_exchange());
    send_plant(1, {10.0f, 20.0f, 30.0f, 40.0f}, "B-1", 0);
    send_plant(2, {10.25f, 19.75f, 30.0f, 40.5f}, "B-1", 0);  // each within 0.5
    send_plant(3, {10.0f, 20.0f, 30.0f, 41.0f}, "B-1", 0);    // the last beyond it
    send_plant(4, {10.0f, 20.0f, 30.0f, 41.0f}, "B-2", 0);    // a new batch only
    EXPECT_EQ(values_on("plant/TEMPS"),
              (std::vector<std::string>{"[10.0,20.0,30.0,40.0]", "[10.0,20.0,30.0,41.0]"}));
    EXPECT_EQ(values_on("plant/BATCH"), (std::vector<std::string>{"\"B-1\"", "\"B-2\""}));
}

TEST_F(ArraysStringsTest, SparkplugBirthsCarryTheArrayTypeAndTheText) {
    GatewayOptions options;
    options.sections = "sparkplug:\n  group_id: plant1\n";
    start(plant_exchange(), "", options);
    send(plant(1, {1.0f, 2.0f, 3.0f, 4.0f}, "B-1", 0b0001));
    const auto birth =
        recorder_->wait_for_message("spBv1.0/plant1/DBIRTH/test-gw/plant", nullptr, 10s);
    ASSERT_TRUE(birth.has_value());
    org::eclipse::tahu::protobuf::Payload proto;
    ASSERT_TRUE(proto.ParseFromString(birth->payload));
    std::map<std::string, const org::eclipse::tahu::protobuf::Payload::Metric*> metrics;
    for (const auto& m : proto.metrics()) metrics[m.name()] = &m;
    ASSERT_TRUE(metrics.count("TEMPS") && metrics.count("BATCH") && metrics.count("FLAGS"));
    EXPECT_EQ(metrics["TEMPS"]->datatype(), 30u);  // FloatArray
    EXPECT_EQ(metrics["TEMPS"]->bytes_value().size(), 16u);
    EXPECT_EQ(metrics["FLAGS"]->datatype(), 32u);  // BooleanArray: count, then the bits
    EXPECT_EQ(metrics["FLAGS"]->bytes_value(), std::string("\x04\x00\x00\x00\x80", 5));
    // Eclipse Tahu reads the string; it predates the array types.
    const auto decoded = tahu_decode(birth->payload);
    for (const auto& m : decoded["metrics"]) {
        if (m["name"] != "BATCH") continue;
        EXPECT_EQ(m["type"], "String");
        EXPECT_EQ(m["value"], "B-1");
    }
}

class ArrayStringWritesTest : public GatewayTest {
protected:
    void SetUp() override {
        capture_ = std::make_unique<UdpClient>();
        start(ExchangeYaml::produce("sp", "10.1.2.3", 10,
                                    "127.0.0.1:" + std::to_string(capture_->port()))
                  .period_ms(20)
                  .tag("VALVES", "0.0", "int", "count: 3, writable: true, min: 0, max: 100")
                  .tag("RECIPE", "6.0", "string", "length: 6, writable: true, initial: \"S-1\"")
                  .str());
        ASSERT_TRUE(capture_->receive(5s).has_value());
    }

    json write(const std::string& tag, const std::string& payload) {
        const auto result = write_result("sp/" + tag + "/set", payload);
        return result.empty() ? json() : json::parse(result);
    }

    /// The field's bytes in the gateway's current image.
    std::string field(std::size_t offset, std::size_t size) {
        const auto bytes = capture_->latest(5s).value_or(std::vector<std::byte>(64));
        std::string out;
        for (std::size_t i = 0; i < size; ++i) out += static_cast<char>(bytes[32 + offset + i]);
        return out;
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(ArrayStringWritesTest, AWholeArrayOneElementAndATextReachTheWire) {
    EXPECT_EQ(field(6, 6), std::string("S-1\0\0\0", 6));
    EXPECT_EQ(write("VALVES", "[10, 20, 30]"), json({{"ok", true}}));
    EXPECT_EQ(field(0, 6), std::string("\x0a\x00\x14\x00\x1e\x00", 6));
    EXPECT_EQ(write("VALVES", R"({"index": 1, "value": 25})"), json({{"ok", true}}));
    EXPECT_EQ(field(0, 6), std::string("\x0a\x00\x19\x00\x1e\x00", 6));
    expect_field(topic("sp/VALVES"), "value", "[10,25,30]");
    EXPECT_EQ(write("RECIPE", "\"\xC3\xA9t\xC3\xA9\""), json({{"ok", true}}));  // "été"
    EXPECT_EQ(field(6, 6), std::string("\xE9t\xE9\0\0\0", 6));
    expect_field(topic("sp/RECIPE"), "value", "\"\xC3\xA9t\xC3\xA9\"");
}

TEST_F(ArrayStringWritesTest, BadShapesTextsAndElementsAreRefusedWithTheirReason) {
    EXPECT_EQ(write("VALVES", "[10, 20]")["error"],
              R"(expected an array of 3 values or {"index": i, "value": v})");
    EXPECT_EQ(write("VALVES", "[10, 200, 30]")["error"], "element 1: above max 100");
    EXPECT_EQ(write("VALVES", R"({"index": 3, "value": 1})")["error"],
              "index 3 beyond the 3 elements");
    EXPECT_EQ(write("RECIPE", "\"WINTER-2\"")["error"], "longer than the tag's 6 bytes");
    EXPECT_EQ(write("RECIPE", "\"5\xE2\x82\xAC\"")["error"],
              "has a character with no Latin-1 form");
    EXPECT_EQ(write("RECIPE", "42")["error"], "expected a string");
    EXPECT_EQ(field(0, 12), std::string("\0\0\0\0\0\0S-1\0\0\0", 12));  // nothing changed
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
