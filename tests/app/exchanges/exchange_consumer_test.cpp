// ExchangeConsumer's data path (issue #6) through the JSON tree: a datagram's decode,
// report-by-exception and tag publications allocate nothing once warm, when the publisher gives
// buffers back as the MQTT client does (Client::publish).

#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/support/count_allocations.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr int kTags = 10;

core::plan::ExchangePlan turbine_plan() {
    core::plan::ExchangeSpec spec;
    spec.name = "e1";
    spec.direction = core::plan::Direction::consume;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = 1;
    spec.length = 4 * kTags;
    spec.topic = "turbine1/e1";
    for (int i = 0; i < kTags; ++i) {
        core::plan::TagSpec tag;
        tag.name = "GENERATOR_TAG_" + std::to_string(i);
        tag.address = {static_cast<std::uint16_t>(4 * i), 0};
        tag.type = core::plan::TagType::dint;
        spec.tags.push_back(tag);
    }
    return core::plan::make_exchange_plan(std::move(spec), "acme/blumenau");
}

TEST(ExchangeConsumerDataPath, PublishesEveryChangedTagWithoutAllocatingOnceWarm) {
    // Like Client::publish: takes the content, leaves the buffers of the one before.
    test::JsonTreeRecorder uns({}, test::RecordingPublisher::Mode::keep_last);
    const auto& published = uns.publisher.count;
    const auto& last = uns.publisher.last;
    ExchangeConsumer consumer(turbine_plan(), uns.northbound());

    std::array<std::byte, 4 * kTags> data{};
    core::wire::Datagram datagram;
    datagram.header.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    datagram.header.exchange_id = 1;
    datagram.header.time_s = 1732291200;
    datagram.data = data;
    auto now = core::MonoTime{} + 1h;
    auto wall = core::WallTime{} + 1h;
    std::int64_t value = 1000;
    auto datagrams = [&](int count) {
        for (int d = 0; d < count; ++d) {
            ++datagram.header.request_id;
            ++value;
            for (int i = 0; i < kTags; ++i) {
                core::plan::encode_value(data, core::plan::TagType::dint,
                                         {static_cast<std::uint16_t>(4 * i), 0},
                                         core::plan::Value{value * (i + 1)});
            }
            now += 10ms;
            wall += 10ms;
            consumer.on_datagram(datagram, now, wall);
        }
    };
    // Warm: the exchange is ok, the buffers fit every payload, and a second of arrivals has
    // filled the arrival-rate window (ArrivalStats keeps that second's arrival times).
    datagrams(150);
    const std::size_t before = published;
    EXPECT_EQ(test::allocations_during([&] { datagrams(100); }), 0u);
    EXPECT_EQ(published - before, 100u * kTags);  // every tag changed in every datagram
    EXPECT_EQ(last.topic, "acme/blumenau/turbine1/e1/GENERATOR_TAG_9");
    EXPECT_NE(last.payload.find("\"value\":" + std::to_string(value * kTags)), std::string::npos);
}

TEST(ExchangeConsumerDataPath, BatchModeAddsOneValuesMessagePerDatagram) {
    // Issue #6, mqtt.batch: besides the tag topics, {exchange}/_values with every tag that
    // changed in the datagram, same value encoding, not retained, in the batch lane.
    app::northbound::json_tree::PublishSettings settings;
    settings.batch = true;
    test::JsonTreeRecorder uns(settings);
    auto& published = uns.publisher.published;
    auto plan = turbine_plan();
    plan.timestamp = core::plan::TimestampSource::producer;  // the datagram's 2024 time
    ExchangeConsumer consumer(std::move(plan), uns.northbound());

    std::array<std::byte, 4 * kTags> data{};
    for (int i = 0; i < kTags; ++i) {
        core::plan::encode_value(data, core::plan::TagType::dint,
                                 {static_cast<std::uint16_t>(4 * i), 0},
                                 core::plan::Value{std::int64_t{100 + i}});
    }
    core::wire::Datagram datagram;
    datagram.header.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    datagram.header.exchange_id = 1;
    datagram.header.request_id = 1;
    datagram.header.time_s = 1732291200;
    datagram.data = data;
    const auto now = core::MonoTime{} + 1h;
    consumer.on_datagram(datagram, now, core::WallTime{} + 1h);

    const auto values = std::find_if(published.begin(), published.end(), [](const auto& m) {
        return m.topic == "acme/blumenau/turbine1/e1/_values";
    });
    ASSERT_NE(values, published.end());
    EXPECT_TRUE(values->batch_lane);
    EXPECT_FALSE(values->retain);
    EXPECT_EQ(values->payload,
              R"({"timestamp":1732291200000,"quality":"good","values":{)"
              R"("GENERATOR_TAG_0":100,"GENERATOR_TAG_1":101,"GENERATOR_TAG_2":102,)"
              R"("GENERATOR_TAG_3":103,"GENERATOR_TAG_4":104,"GENERATOR_TAG_5":105,)"
              R"("GENERATOR_TAG_6":106,"GENERATOR_TAG_7":107,"GENERATOR_TAG_8":108,)"
              R"("GENERATOR_TAG_9":109}})");

    // Only what changed goes into the next one.
    published.clear();
    core::plan::encode_value(data, core::plan::TagType::dint, {12, 0},
                             core::plan::Value{std::int64_t{-7}});
    ++datagram.header.request_id;
    consumer.on_datagram(datagram, now + 10ms, core::WallTime{} + 1h + 10ms);
    const auto next = std::find_if(published.begin(), published.end(),
                                   [](const auto& m) { return m.batch_lane; });
    ASSERT_NE(next, published.end());
    EXPECT_NE(next->payload.find(R"("values":{"GENERATOR_TAG_3":-7}})"), std::string::npos)
        << next->payload;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
