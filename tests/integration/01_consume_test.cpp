// Consumed exchanges become retained MQTT topics: values of every type, timestamps, report by
// exception with deadband, stale after the timeout, bad on mismatch, counters in `_status`.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;

const std::string every_type_exchange = ExchangeYaml::consume("unit1", "10.0.0.1", 1)
                                            .length(40)
                                            .period_ms(100)
                                            .timeout_ms(400)
                                            .key("timestamp", "producer")
                                            .tag("RUN", "0.0", "bit")
                                            .tag("TRIP", "0.7", "bit")
                                            .tag("MODE", "1.0", "byte")
                                            .tag("PRESSURE", "2.0", "int", "deadband: 5")
                                            .tag("COUNT", "5.0", "word")
                                            .tag("FLOW", "7.0", "dint")
                                            .tag("ENERGY", "11.0", "udint")
                                            .tag("TEMP", "15.0", "real")
                                            .tag("TOTAL", "19.0", "lint")
                                            .tag("PRECISE", "27.0", "lreal")
                                            .tag("MARKER", "35.0", "word")
                                            .str();

DatagramBuilder every_type_datagram(std::uint16_t rid) {
    DatagramBuilder b("10.0.0.1", 1, 40);
    b.request_id(rid)
        .timestamp(1695231678, 250000000)
        .set("0.0", TagType::bit, true)
        .set("0.7", TagType::bit, false)
        .set("1.0", TagType::byte, std::uint64_t{200})
        .set("2.0", TagType::int_, std::int64_t{-2})
        .set("5.0", TagType::word, std::uint64_t{65535})
        .set("7.0", TagType::dint, std::int64_t{-100000})
        .set("11.0", TagType::udint, std::uint64_t{3000000000})
        .set("15.0", TagType::real, -273.15f)
        .set("19.0", TagType::lint, std::int64_t{-2})
        .set("27.0", TagType::lreal, 65900.0)
        .set("35.0", TagType::word, std::uint64_t{rid});
    return b;
}

class ConsumeTest : public GatewayTest {};

TEST_F(ConsumeTest, EveryTypeIsPublishedRetainedWithProducerTimestamp) {
    start(every_type_exchange);
    send(every_type_datagram(1).build());
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"RUN", "true"},    {"TRIP", "false"},      {"MODE", "200"},          {"PRESSURE", "-2"},
        {"COUNT", "65535"}, {"FLOW", "-100000"},    {"ENERGY", "3000000000"}, {"TEMP", "-273.15"},
        {"TOTAL", "-2"},    {"PRECISE", "65900.0"},
    };
    for (const auto& [tag, value] : expected) {
        const auto m = expect_field(topic("unit1/" + tag), "value", value);
        const auto payload = json::parse(m.payload);
        EXPECT_EQ(payload["quality"], "good") << tag;
        EXPECT_EQ(payload["timestamp"], 1695231678250) << tag;
    }
    // A subscriber arriving later gets every value from the broker's retained store.
    MqttRecorder late(broker_->url(), {"test/unit1/+"}, "late-subscriber");
    ASSERT_TRUE(late.wait_for([](const auto& all) { return all.size() >= 11; }));
    for (const auto& m : late.messages()) EXPECT_TRUE(m.retained) << m.topic;
}

TEST_F(ConsumeTest, RawPayloadIsTheBareValue) {
    start(every_type_exchange, "  payload: raw\n");
    send(every_type_datagram(1).build());
    EXPECT_TRUE(recorder_->wait_for_message(topic("unit1/TEMP"),
                                            [](const std::string& p) { return p == "-273.15"; }));
    EXPECT_TRUE(recorder_->wait_for_message(topic("unit1/RUN"),
                                            [](const std::string& p) { return p == "true"; }));
}

TEST_F(ConsumeTest, DeadbandSuppressesSmallChangesAndUnchangedValuesAreNotRepublished) {
    start(every_type_exchange);
    auto d = every_type_datagram(1);
    d.set("2.0", TagType::int_, std::int64_t{100});
    send(d.build());
    expect_field(topic("unit1/PRESSURE"), "value", "100");
    const auto after_first = recorder_->messages_on(topic("unit1/RUN")).size();

    d.request_id(2)
        .set("2.0", TagType::int_, std::int64_t{104})
        .set("35.0", TagType::word, std::uint64_t{2});
    send(d.build());
    // MARKER changes with every datagram; once it is seen, the datagram was fully handled.
    expect_field(topic("unit1/MARKER"), "value", "2");
    d.request_id(3)
        .set("2.0", TagType::int_, std::int64_t{106})
        .set("35.0", TagType::word, std::uint64_t{3});
    send(d.build());
    expect_field(topic("unit1/MARKER"), "value", "3");

    std::vector<std::string> pressures;
    for (const auto& m : recorder_->messages_on(topic("unit1/PRESSURE"))) {
        pressures.push_back(json::parse(m.payload)["value"].dump());
    }
    EXPECT_EQ(pressures, (std::vector<std::string>{"100", "106"}));
    // RUN never changed: published once only.
    EXPECT_EQ(recorder_->messages_on(topic("unit1/RUN")).size(), after_first);
}

TEST_F(ConsumeTest, StaleAfterTimeoutThenGoodAgain) {
    start(every_type_exchange);
    send(every_type_datagram(1).build());
    expect_field(topic("unit1/TEMP"), "quality", "\"good\"");
    // No datagram: after timeout_ms every tag is republished stale with its last value.
    const auto stale = expect_field(topic("unit1/TEMP"), "quality", "\"stale\"");
    EXPECT_EQ(json::parse(stale.payload)["value"].dump(), "-273.15");
    expect_field(topic("unit1/RUN"), "quality", "\"stale\"");
    expect_field(topic("unit1/_status"), "state", "\"stale\"");

    const auto from = recorder_->count();
    send(every_type_datagram(2).build());
    expect_field(topic("unit1/TEMP"), "quality", "\"good\"", from);
    expect_field(topic("unit1/RUN"), "quality", "\"good\"", from);
    expect_field(topic("unit1/_status"), "state", "\"ok\"", from);
}

TEST_F(ConsumeTest, SignatureMismatchTurnsTagsBad) {
    auto yaml = every_type_exchange;
    yaml.replace(yaml.find("    topic: unit1"), 0, "    signature: \"2.5\"\n");
    start(yaml);
    send(every_type_datagram(1).signature(2, 5).build());
    expect_field(topic("unit1/TEMP"), "quality", "\"good\"");
    // A newer minor is compatible.
    send(every_type_datagram(2).signature(2, 6).build());
    expect_field(topic("unit1/MARKER"), "value", "2");
    // Another major is not: the data is not consumed and the tags turn bad.
    auto other = every_type_datagram(3).signature(3, 0);
    other.set("15.0", TagType::real, 1.5f);
    send(other.build());
    const auto bad = expect_field(topic("unit1/TEMP"), "quality", "\"bad\"");
    EXPECT_EQ(json::parse(bad.payload)["value"].dump(), "-273.15");
    expect_field(topic("unit1/_status"), "state", "\"signature_mismatch\"");
}

TEST_F(ConsumeTest, LengthMismatchTurnsTagsBad) {
    start(every_type_exchange);
    send(every_type_datagram(1).build());
    expect_field(topic("unit1/TEMP"), "quality", "\"good\"");
    auto shorter = every_type_datagram(2);
    shorter.data().resize(39);
    send(shorter.build());
    expect_field(topic("unit1/TEMP"), "quality", "\"bad\"");
    expect_field(topic("unit1/_status"), "state", "\"length_mismatch\"");
    send(every_type_datagram(3).build());
    expect_field(topic("unit1/TEMP"), "quality", "\"good\"");
}

TEST_F(ConsumeTest, DuplicatesAndGapsAreCountedInStatus) {
    start(every_type_exchange);
    for (const std::uint16_t rid : {65534, 65535, 65535, 0, 3, 2}) {
        send(every_type_datagram(rid).build());
    }
    // 65535 -> 0 is in sequence; 0 -> 3 misses 2; 2 after 3 is out of order.
    const auto status =
        recorder_->wait_for_message(topic("unit1/_status"), [](const std::string& p) {
            const auto j = json::parse(p);
            return j["received"] == 6;
        });
    ASSERT_TRUE(status.has_value());
    const auto j = json::parse(status->payload);
    EXPECT_EQ(j["accepted"], 4);
    EXPECT_EQ(j["duplicates"], 1);
    EXPECT_EQ(j["missed"], 2);
    EXPECT_EQ(j["out_of_order"], 1);
    EXPECT_EQ(j["request_id"], 3);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
