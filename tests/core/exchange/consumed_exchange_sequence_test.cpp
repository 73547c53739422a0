// ConsumedExchange, docs/protocol.md §4 rule 6: which request ids are new samples; restarts.

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/exchange/consumed_exchange_samples.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

TEST(ConsumerRules, Rule6FirstDatagramResynchronisesWithoutCounting) {
    ConsumedExchange exchange(make_plan());
    EXPECT_TRUE(feed(exchange, sample(500)).accepted());
    EXPECT_EQ(exchange.counters().missed, 0u);
}

TEST(ConsumerRules, Rule6NextRequestIdIsANewSample) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(10));
    EXPECT_TRUE(feed(exchange, sample(11, 15, {}, std::byte{0x22})).accepted());
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(to_hex(exchange.image()), "222222222222222222222222222222");
}

TEST(ConsumerRules, Rule6GapCountsMissedSamples) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(10));
    EXPECT_TRUE(feed(exchange, sample(14)).accepted());
    EXPECT_EQ(exchange.counters().missed, 3u);
    EXPECT_TRUE(feed(exchange, sample(14 + 32767)).accepted());
    EXPECT_EQ(exchange.counters().missed, 3u + 32766u);
}

TEST(ConsumerRules, Rule6GapAcrossTheWrap) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(65534));
    EXPECT_TRUE(feed(exchange, sample(1)).accepted());
    EXPECT_EQ(exchange.counters().missed, 2u);
}

TEST(ConsumerRules, Rule6DuplicateIsDropped) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(10, 15, {}, std::byte{0x01}));
    const auto outcome = feed(exchange, sample(10, 15, {}, std::byte{0x02}), 10ms);
    EXPECT_EQ(outcome.dropped, DropReason::duplicate);
    EXPECT_FALSE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_EQ(exchange.counters().duplicates, 1u);
    EXPECT_EQ(exchange.counters().accepted, 1u);
    EXPECT_EQ(to_hex(exchange.image()), "010101010101010101010101010101");
    EXPECT_EQ(exchange.last_accepted(), at(0ms));
}

TEST(ConsumerRules, Rule6DuplicateDoesNotRestartTheUpdateTimer) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(10), 0ms);
    feed(exchange, sample(10), 2000ms);
    EXPECT_EQ(exchange.next_deadline(), at(3000ms));
    EXPECT_TRUE(exchange.on_tick(at(3000ms)));
}

TEST(ConsumerRules, Rule6LateDatagramIsDropped) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(10, 15, {}, std::byte{0x01}));
    const auto outcome = feed(exchange, sample(9, 15, {}, std::byte{0x02}));
    EXPECT_EQ(outcome.dropped, DropReason::out_of_order);
    EXPECT_FALSE(outcome.state_changed);
    EXPECT_EQ(exchange.counters().out_of_order, 1u);
    EXPECT_EQ(exchange.last_header().request_id, 10);
    EXPECT_EQ(to_hex(exchange.image()), "010101010101010101010101010101");
}

/// A sample stamped by the producer's clock at `seconds`.
Sample stamped(std::uint16_t request_id, std::uint32_t seconds, std::uint32_t nanoseconds = 0) {
    Sample s = sample(request_id);
    s.header.time_s = seconds;
    s.header.time_ns = nanoseconds;
    return s;
}

TEST(ConsumerRules, Rule6OldRequestIdWithTheProducerTimeMovedForwardIsARestart) {
    ConsumedExchange exchange(make_plan(15, 0ms));
    feed(exchange, stamped(20000, 947817150));
    // The PLC restarted: its ids begin again, its clock (even one in the year 2000) goes on.
    const auto outcome = feed(exchange, stamped(1, 947817160));
    EXPECT_TRUE(outcome.accepted());
    EXPECT_EQ(exchange.counters().restarts, 1u);
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(exchange.counters().out_of_order, 0u);
    EXPECT_EQ(exchange.last_header().request_id, 1);
    // Resynchronised: the ids that follow are in sequence again.
    EXPECT_TRUE(feed(exchange, stamped(2, 947817160, 100000000)).accepted());
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(exchange.counters().accepted, 3u);
}

TEST(ConsumerRules, Rule6OldRequestIdWithTheSameOrAnOlderTimeIsLate) {
    ConsumedExchange exchange(make_plan(15, 0ms));
    feed(exchange, stamped(100, 1000, 500));
    EXPECT_EQ(feed(exchange, stamped(99, 1000, 500)).dropped, DropReason::out_of_order);
    EXPECT_EQ(feed(exchange, stamped(99, 1000, 400)).dropped, DropReason::out_of_order);
    EXPECT_EQ(feed(exchange, stamped(99, 999, 900)).dropped, DropReason::out_of_order);
    EXPECT_EQ(exchange.counters().restarts, 0u);
    EXPECT_EQ(exchange.counters().out_of_order, 3u);
}

TEST(ConsumerRules, Rule6WithoutTimestampsAnOldRequestIdIsLate) {
    ConsumedExchange exchange(make_plan(15, 0ms));
    feed(exchange, stamped(100, 1000));
    EXPECT_EQ(feed(exchange, stamped(1, 0)).dropped, DropReason::out_of_order);
    feed(exchange, sample(101));  // a datagram without a timestamp
    EXPECT_EQ(feed(exchange, stamped(1, 2000)).dropped, DropReason::out_of_order);
    EXPECT_EQ(exchange.counters().restarts, 0u);
}

TEST(ConsumerRules, Rule6HalfTheRangeAheadIsLate) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(10));
    EXPECT_EQ(feed(exchange, sample(10 + 32768)).dropped, DropReason::out_of_order);
    EXPECT_EQ(feed(exchange, sample(65535)).dropped, DropReason::out_of_order);
    EXPECT_EQ(exchange.counters().missed, 0u);
}

TEST(ConsumerRules, Rule6ResynchronisesAfterATimeout) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(100), 0ms);
    ASSERT_TRUE(exchange.on_tick(at(3000ms)));
    const auto outcome = feed(exchange, sample(5), 4000ms);
    EXPECT_TRUE(outcome.accepted());
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(exchange.counters().out_of_order, 0u);
}

TEST(ConsumerRules, Rule6ResynchronisesAfterASignatureChange) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    feed(exchange, sample(100, 15, Signature{2, 5}));
    const auto outcome = feed(exchange, sample(50, 15, Signature{2, 6}));
    EXPECT_TRUE(outcome.accepted());
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(exchange.counters().out_of_order, 0u);
    EXPECT_EQ(exchange.last_header().request_id, 50);
}

TEST(ConsumerRules, Rule6ResynchronisesAfterALengthMismatch) {
    ConsumedExchange exchange(make_plan());
    feed(exchange, sample(100));
    EXPECT_EQ(feed(exchange, sample(101, 10)).dropped, DropReason::length_mismatch);
    const auto outcome = feed(exchange, sample(100));
    EXPECT_TRUE(outcome.accepted());
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_EQ(exchange.counters().duplicates, 0u);
}

TEST(ConsumerRules, Rule6ResynchronisesAfterASignatureMismatch) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    feed(exchange, sample(100, 15, Signature{2, 5}));
    feed(exchange, sample(101, 15, Signature{1, 0}));
    EXPECT_TRUE(feed(exchange, sample(7, 15, Signature{2, 5})).accepted());
    EXPECT_EQ(exchange.counters().missed, 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
