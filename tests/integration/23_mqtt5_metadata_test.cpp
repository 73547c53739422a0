// MQTT 5 metadata end to end (docs/mqtt-api.md, "MQTT 5 metadata"): the real binary against a
// real Mosquitto. User properties, content type and expiry read back by an MQTT 5 subscriber;
// topic aliases read on the wire by a relay between the gateway and its broker: a topic's name
// is sent once per connection, then its alias alone, and again after the broker restarted.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mqtt_relay.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

std::string line_exchange() {
    return ExchangeYaml::consume("line", "10.0.0.1", 1)
        .length(8)
        .period_ms(100)
        .timeout_ms(60000)
        .key("location", "{ area: turbine-hall, asset: turbine-1/lube-oil-system }")
        .tag("SPEED", "0.0", "dint", "unit: rpm")
        .tag("COUNT", "4.0", "dint")
        .str();
}

std::vector<std::byte> line(std::uint16_t rid, std::int64_t speed) {
    DatagramBuilder builder("10.0.0.1", 1, 8);
    builder.request_id(rid);
    builder.set("0.0", TagType::dint, Value{speed});
    builder.set("4.0", TagType::dint, Value{std::int64_t{rid}});
    return builder.build();
}

class Mqtt5MetadataTest : public GatewayTest {};

TEST_F(Mqtt5MetadataTest, DataMessagesCarryTheChosenPropertiesTheirTypeAndExpiry) {
    start(line_exchange(),
          "  properties: [unit, quality, source_time, exchange, producer]\n"
          "  message_expiry_s: 600\n");
    send(line(1, 3000));
    const auto speed = recorder_->wait_for_message(topic("line/SPEED"), nullptr, 10s);
    ASSERT_TRUE(speed.has_value());
    const auto timestamp = json::parse(speed->payload)["timestamp"].get<std::int64_t>();
    EXPECT_EQ(speed->user_properties, (std::vector<std::pair<std::string, std::string>>{
                                          {"unit", "rpm"},
                                          {"quality", "good"},
                                          {"source_time", std::to_string(timestamp)},
                                          {"exchange", "line"},
                                          {"producer", "10.0.0.1"}}));
    EXPECT_EQ(speed->content_type, "application/json");
    EXPECT_EQ(speed->payload_format, 1);
    EXPECT_GT(speed->message_expiry_s, 0);
    EXPECT_LE(speed->message_expiry_s, 600);
    // No unit, no property of it.
    const auto count = recorder_->wait_for_message(topic("line/COUNT"), nullptr, 10s);
    ASSERT_TRUE(count.has_value());
    EXPECT_EQ(count->user_properties.front().first, "quality");
    // Never on what describes the exchange; the state is text.
    const auto status = recorder_->wait_for_message(topic("line/_status"), nullptr, 10s);
    ASSERT_TRUE(status.has_value());
    EXPECT_EQ(status->message_expiry_s, -1);
    EXPECT_EQ(status->content_type, "application/json");
    EXPECT_TRUE(status->user_properties.empty());
    const auto state = recorder_->wait_for_message(availability_topic(), nullptr, 10s);
    ASSERT_TRUE(state.has_value());
    EXPECT_EQ(state->content_type, "text/plain");
}

TEST_F(Mqtt5MetadataTest, DescribePayloadsOffSendsNoContentTypeNorFormatButTheOtherProperties) {
    start(line_exchange(), "  describe_payloads: false\n  properties: [unit]\n");
    send(line(1, 3000));
    const auto speed = recorder_->wait_for_message(topic("line/SPEED"), nullptr, 10s);
    ASSERT_TRUE(speed.has_value());
    EXPECT_EQ(speed->content_type, "");
    EXPECT_EQ(speed->payload_format, -1);
    EXPECT_EQ(speed->user_properties,
              (std::vector<std::pair<std::string, std::string>>{{"unit", "rpm"}}));
    const auto state = recorder_->wait_for_message(availability_topic(), nullptr, 10s);
    ASSERT_TRUE(state.has_value());
    EXPECT_EQ(state->content_type, "");
}

TEST_F(Mqtt5MetadataTest, ATopicIsNamedOncePerConnectionThenSentByItsAlias) {
    std::unique_ptr<MqttRelay> relay;
    GatewayOptions options;
    options.url_through = [&](std::uint16_t port) {
        relay = std::make_unique<MqttRelay>(port);
        return relay->url();
    };
    const std::string long_topics =
        "  topic_template: \"{base}/acme-chemicals/site-ludwigshafen/{area}/{asset}/{tag}\"\n"
        "  topic_aliases: true\n";
    start(line_exchange(), long_topics, options);
    const auto speed = topic(
        "acme-chemicals/site-ludwigshafen/turbine-hall/"
        "turbine-1/lube-oil-system/SPEED");
    // Publications of SPEED on connection `c`: (named, alias) each.
    const auto sent = [&](const MqttRelay::Events& events, std::size_t c) {
        std::vector<std::pair<bool, std::uint16_t>> out;
        std::optional<std::uint16_t> alias;
        for (const auto& e : events) {
            if (e.connection != c || !e.from_client() || e.closed()) continue;
            const auto& p = *e.packet;
            if (p.type != PacketType::publish) continue;
            if (p.topic == speed) alias = p.topic_alias;
            if (p.topic == speed || (p.topic.empty() && alias && p.topic_alias == alias)) {
                out.emplace_back(!p.topic.empty(), p.topic_alias.value_or(0));
            }
        }
        return out;
    };
    const auto published = [&](std::size_t c, std::size_t n) {
        return relay->wait_for([&](const auto& events) { return sent(events, c).size() >= n; },
                               10s);
    };
    for (std::uint16_t rid = 1; rid <= 3; ++rid) {
        send(line(rid, 3000 + rid));
        expect_field(speed, "value", std::to_string(3000 + rid));
    }
    ASSERT_TRUE(published(0, 3));
    const auto first = sent(relay->events(), 0);
    EXPECT_TRUE(first[0].first);
    EXPECT_NE(first[0].second, 0);
    EXPECT_FALSE(first[1].first);
    EXPECT_EQ(first[1].second, first[0].second);
    // The subscriber is handed the topic's name whatever the gateway sent.
    EXPECT_EQ(recorder_->messages_on(speed).size(), 3u);

    // A new connection knows no alias: the name is sent again first.
    broker_->stop();
    broker_->start();
    wait_online(recorder_->count());
    std::size_t second = 0;
    for (const auto& e : relay->events()) second = std::max(second, e.connection);
    ASSERT_GE(second, 1u);
    for (std::uint16_t rid = 4; rid <= 5; ++rid) send(line(rid, 3000 + rid));
    ASSERT_TRUE(published(second, 2));
    const auto again = sent(relay->events(), second);
    EXPECT_TRUE(again[0].first);
    EXPECT_FALSE(again[1].first);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
