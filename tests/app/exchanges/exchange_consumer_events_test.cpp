// What a consumed exchange reports north, read through a fake northbound: the tags a
// datagram changed, in one batch with their quality and time; the exchange going up and down;
// its status. No protocol in between, and time is passed in.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/core/exchange/change_log.hpp"
#include "eip2mqtt/core/exchange/change_pacer.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::exchange::ConsumeState;
using core::quality::Quality;

core::plan::ExchangePlan two_tag_plan() {
    core::plan::ExchangeSpec spec;
    spec.name = "e1";
    spec.direction = core::plan::Direction::consume;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = 1;
    spec.length = 8;
    spec.period = 100ms;  // stale after 300 ms without data
    spec.topic = "e1";
    for (const auto* name : {"A", "B"}) {
        core::plan::TagSpec tag;
        tag.name = name;
        tag.address = {static_cast<std::uint16_t>(name[0] == 'A' ? 0 : 4), 0};
        tag.type = core::plan::TagType::dint;
        spec.tags.push_back(tag);
    }
    auto plan = core::plan::make_exchange_plan(std::move(spec), "acme");
    plan.timestamp = core::plan::TimestampSource::receive;
    return plan;
}

class ConsumerEvents : public ::testing::Test {
protected:
    /// A datagram with A = a, B = b, the next request id, 10 ms after the last.
    void datagram(std::int64_t a, std::int64_t b) {
        core::plan::encode_value(data_, core::plan::TagType::dint, {0, 0}, core::plan::Value{a});
        core::plan::encode_value(data_, core::plan::TagType::dint, {4, 0}, core::plan::Value{b});
        core::wire::Datagram d;
        d.header.producer_id = *core::wire::parse_producer_id("10.0.0.1");
        d.header.exchange_id = 1;
        d.header.request_id = ++rid_;
        d.data = data_;
        advance(10ms);
        consumer_.on_datagram(d, now_, wall_);
    }
    /// A datagram of 6 data bytes where 8 are configured: a length mismatch.
    void short_datagram() {
        core::wire::Datagram d;
        d.header.producer_id = *core::wire::parse_producer_id("10.0.0.1");
        d.header.exchange_id = 1;
        d.header.request_id = ++rid_;
        d.data = std::span<const std::byte>(data_).first(6);
        advance(1ms);
        consumer_.on_datagram(d, now_, wall_);
    }
    /// A good datagram stamped `offset` off the receive time, 1 ms after the last.
    void stamped_datagram(std::chrono::milliseconds offset) {
        core::wire::Datagram d;
        d.header.producer_id = *core::wire::parse_producer_id("10.0.0.1");
        d.header.exchange_id = 1;
        d.header.request_id = ++rid_;
        advance(1ms);
        const auto stamp = core::wire_time(wall_ + offset);
        d.header.time_s = stamp.seconds;
        d.header.time_ns = stamp.nanoseconds;
        d.data = data_;
        consumer_.on_datagram(d, now_, wall_);
    }
    std::size_t count(const std::string& event) const {
        return static_cast<std::size_t>(
            std::count(north_.events.begin(), north_.events.end(), event));
    }
    void advance(std::chrono::milliseconds step) {
        now_ += step;
        wall_ += step;
    }
    std::int64_t wall_ms() const {
        return std::chrono::duration_cast<std::chrono::milliseconds>(wall_.time_since_epoch())
            .count();
    }

    std::array<std::byte, 8> data_{};
    std::uint16_t rid_ = 0;
    core::MonoTime now_ = core::MonoTime{} + 1h;
    core::WallTime wall_ = core::WallTime{} + 1h;
    test::RecordingNorthbound north_;
    ExchangeConsumer consumer_{two_tag_plan(), north_};
};

TEST_F(ConsumerEvents, TheFirstDatagramReportsEveryTagThenTheExchangeUpThenItsStatus) {
    datagram(1, 2);
    EXPECT_EQ(north_.events, (std::vector<std::string>{"samples", "state", "status"}));
    ASSERT_EQ(north_.batches.size(), 1u);
    const auto& batch = north_.batches[0];
    EXPECT_EQ(batch.exchange, "e1");
    EXPECT_EQ(batch.quality, Quality::good);
    EXPECT_EQ(batch.timestamp_ms, wall_ms());  // timestamp: receive
    EXPECT_FALSE(batch.all_tags);
    ASSERT_EQ(batch.samples.size(), 2u);
    EXPECT_EQ(batch.samples[1].tag, 1u);
    EXPECT_TRUE(core::plan::same_value(batch.samples[1].value, core::plan::Value{std::int64_t{2}}));
    ASSERT_EQ(north_.states.size(), 1u);
    EXPECT_EQ(north_.states[0].state, ConsumeState::ok);
}

TEST_F(ConsumerEvents, ADatagramReportsOnlyTheTagsItChangedAndNothingWhenNoneChanged) {
    datagram(1, 2);
    datagram(1, 3);
    datagram(1, 3);
    ASSERT_EQ(north_.batches.size(), 2u);
    ASSERT_EQ(north_.batches[1].samples.size(), 1u);
    EXPECT_EQ(north_.batches[1].samples[0].tag, 1u);
    EXPECT_EQ(north_.states.size(), 1u);  // still up: no new state
}

TEST_F(ConsumerEvents, TimeoutReportsEveryTagStaleAndTheExchangeDownThenTheNextDatagramUp) {
    datagram(1, 2);
    north_.events.clear();
    advance(400ms);
    consumer_.on_tick(now_, wall_, false);
    EXPECT_EQ(north_.events, (std::vector<std::string>{"samples", "state", "status"}));
    EXPECT_EQ(north_.batches.back().quality, Quality::stale);
    EXPECT_EQ(north_.batches.back().samples.size(), 2u);       // last values, now stale
    EXPECT_EQ(north_.batches.back().timestamp_ms, wall_ms());  // when it was found stale
    EXPECT_EQ(north_.states.back().state, ConsumeState::stale);

    datagram(1, 2);  // same values, good again: reported, quality changed
    EXPECT_EQ(north_.batches.back().quality, Quality::good);
    EXPECT_EQ(north_.batches.back().samples.size(), 2u);
    EXPECT_EQ(north_.states.back().state, ConsumeState::ok);
}

TEST_F(ConsumerEvents, GoingStaleAndComingBackAreEachLoggedOnce) {
    test::LogCapture log;
    datagram(1, 2);
    log.lines();  // what the first datagram says of the producer's clock
    advance(400ms);
    consumer_.on_tick(now_, wall_, false);
    advance(100ms);
    consumer_.on_tick(now_, wall_, false);
    EXPECT_EQ(log.lines(), std::vector<std::string>{
                               "exchange e1 is stale: no datagram for 300 ms; tags marked stale"});
    advance(2400ms);
    datagram(1, 2);  // 2.5 s after it was found stale
    datagram(1, 3);
    EXPECT_EQ(log.lines(),
              std::vector<std::string>{"exchange e1 is ok again after 2.5 s stale; tags good"});
}

TEST_F(ConsumerEvents, RepublishReportsEveryTagAsAWholeTheStateAndTheStatus) {
    datagram(1, 2);
    north_.events.clear();
    consumer_.republish(now_);
    EXPECT_EQ(north_.events, (std::vector<std::string>{"samples", "state", "status"}));
    EXPECT_TRUE(north_.batches.back().all_tags);
    EXPECT_EQ(north_.batches.back().samples.size(), 2u);
    EXPECT_EQ(north_.states.back().state, ConsumeState::ok);
}

TEST_F(ConsumerEvents, ASampleIsNamedByItsDatagramAndAChangeOfQualityByTheOneBefore) {
    using core::redundancy::SampleKey;
    datagram(1, 2);
    EXPECT_EQ(north_.batches.back().key, (SampleKey{1, 0, 0, 0}));
    advance(400ms);
    consumer_.on_tick(now_, wall_, false);  // stale: no datagram of its own
    EXPECT_EQ(north_.batches.back().key, (SampleKey{1, 0, 0, 1}));
    datagram(1, 3);
    EXPECT_EQ(north_.batches.back().key, (SampleKey{2, 0, 0, 0}));
    // A republish repeats a sample: it names none.
    consumer_.republish(now_);
    EXPECT_FALSE(north_.batches.back().key.has_value());
}

TEST_F(ConsumerEvents, BeforeAnyDatagramThereIsNoValueToReportOnlyTheStateAndStatus) {
    consumer_.republish(now_);
    EXPECT_EQ(north_.events, (std::vector<std::string>{"state", "status"}));
    EXPECT_EQ(north_.states.back().state, ConsumeState::waiting);
}

TEST_F(ConsumerEvents, AlternatingGoodAndShortDatagramsReportQualityAtMostOncePerPeriod) {
    // 200 datagrams over 1.1 s of a 100 ms exchange, a tick between each: each was a
    // republish of both tags, a state and a status, and a log line.
    test::LogCapture log;
    datagram(1, 2);
    north_.events.clear();
    log.lines();
    const auto start = now_;
    for (int i = 0; i < 100; ++i) {
        short_datagram();
        consumer_.on_tick(now_, wall_, false);
        datagram(1, 2);  // 1 ms later: see short_datagram
        consumer_.on_tick(now_, wall_, false);
    }
    // A report a period, plus the burst.
    const auto reports = (now_ - start) / 100ms + core::exchange::ChangePacer::burst;
    EXPECT_LE(count("samples"), static_cast<std::size_t>(reports));
    EXPECT_LE(count("state"), static_cast<std::size_t>(reports));
    EXPECT_LE(count("status"), static_cast<std::size_t>(reports));
    EXPECT_LE(log.lines().size(), core::exchange::ChangeLog::burst + 1);
    // Ending on a good datagram, what was reported ends good a period later at the latest.
    advance(100ms);
    consumer_.on_tick(now_, wall_, false);
    EXPECT_EQ(north_.batches.back().quality, Quality::good);
    EXPECT_EQ(north_.states.back().state, ConsumeState::ok);
    EXPECT_EQ(north_.events.back(), "status");
}

TEST_F(ConsumerEvents, AProducerClockFlippingIsReportedAtMostOncePerPeriod) {
    // Stamps alternately on time and an hour off: the clock flips synced/unsynced each datagram.
    test::LogCapture log;
    stamped_datagram(0ms);
    north_.events.clear();
    log.lines();
    for (int i = 0; i < 100; ++i) {
        stamped_datagram(1h);
        consumer_.on_tick(now_, wall_, false);
        stamped_datagram(0ms);
        consumer_.on_tick(now_, wall_, false);
    }
    EXPECT_LE(count("status"), static_cast<std::size_t>(2 + core::exchange::ChangePacer::burst));
    EXPECT_LE(log.lines().size(), core::exchange::ChangeLog::burst + 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
