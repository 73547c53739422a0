// A consumed exchange with no tags yet: every datagram is checked as usual (length,
// sequence) and counted, and only its `_status` is published, so its traffic can be watched
// before the byte map is known.

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "tests/app/support/json_tree_recorder.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

core::plan::ExchangePlan tagless_plan() {
    core::plan::ExchangeSpec spec;
    spec.name = "10.0.0.9-3";
    spec.direction = core::plan::Direction::consume;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.9");
    spec.exchange_id = 3;
    spec.length = 8;
    spec.period = 1000ms;  // stale after 3 s without data
    spec.topic = "10.0.0.9/3";
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

bool has(const std::string& payload, const std::string& text) {
    return payload.find(text) != std::string::npos;
}

TEST(TaglessConsumer, PublishesOnlyItsStatusWithCountersThatMove) {
    test::JsonTreeRecorder uns;
    const auto& published = uns.publisher.published;
    ExchangeConsumer consumer(tagless_plan(), uns.northbound());
    std::vector<std::byte> data(8);
    core::wire::Datagram datagram;
    datagram.header.producer_id = *core::wire::parse_producer_id("10.0.0.9");
    datagram.header.exchange_id = 3;
    datagram.data = data;
    auto now = core::MonoTime{} + 1h;
    auto wall = core::WallTime{} + 1h;
    for (std::uint16_t rid = 1; rid <= 3; ++rid) {
        datagram.header.request_id = rid;
        now += 20ms;
        wall += 20ms;
        consumer.on_datagram(datagram, now, wall);
    }
    // The first datagram made it ok; at its phase of the second (here: whole seconds), and a
    // second after that at least, the counters that moved since.
    consumer.on_tick(now + 900ms, wall + 900ms, false);
    ASSERT_EQ(published.size(), 1u);
    consumer.on_tick(now + 2s, wall + 2s, false);
    ASSERT_EQ(published.size(), 2u);
    for (const auto& m : published) EXPECT_EQ(m.topic, "acme/10.0.0.9/3/_status");
    EXPECT_TRUE(has(published[0].payload, R"("state":"ok")")) << published[0].payload;
    EXPECT_TRUE(has(published[0].payload, R"("accepted":1,)")) << published[0].payload;
    EXPECT_TRUE(has(published[1].payload, R"("state":"ok")")) << published[1].payload;
    EXPECT_TRUE(has(published[1].payload, R"("received":3,"accepted":3,)")) << published[1].payload;

    // The length is still checked: a longer datagram is a length mismatch, nothing consumed.
    std::vector<std::byte> longer(10);
    datagram.data = longer;
    datagram.header.request_id = 4;
    consumer.on_datagram(datagram, now + 2s + 20ms, wall + 2s + 20ms);
    ASSERT_EQ(published.size(), 3u);
    EXPECT_EQ(published[2].topic, "acme/10.0.0.9/3/_status");
    EXPECT_TRUE(has(published[2].payload, R"("state":"length_mismatch")")) << published[2].payload;
    EXPECT_TRUE(has(published[2].payload, R"("accepted":3,)")) << published[2].payload;
    EXPECT_TRUE(has(published[2].payload, R"("length_mismatches":1,)")) << published[2].payload;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
