#include "eip2mqtt/core/exchange/consumed_exchange.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/exchange/consumed_exchange_samples.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

TEST(ConsumedExchange, StartsWaitingWithoutImage) {
    ConsumedExchange exchange(make_plan());
    EXPECT_EQ(exchange.state(), ConsumeState::waiting);
    EXPECT_FALSE(exchange.has_image());
    EXPECT_TRUE(exchange.image().empty());
    EXPECT_EQ(exchange.last_accepted(), std::nullopt);
    EXPECT_EQ(exchange.next_deadline(), std::nullopt);
    EXPECT_FALSE(exchange.on_tick(at(1h)));
    EXPECT_EQ(exchange.state(), ConsumeState::waiting);
}

TEST(ConsumedExchange, StateNames) {
    EXPECT_EQ(to_string(ConsumeState::waiting), "waiting");
    EXPECT_EQ(to_string(ConsumeState::ok), "ok");
    EXPECT_EQ(to_string(ConsumeState::stale), "stale");
    EXPECT_EQ(to_string(ConsumeState::signature_mismatch), "signature_mismatch");
    EXPECT_EQ(to_string(ConsumeState::length_mismatch), "length_mismatch");
}

TEST(Vectors, V2IsAcceptedAndKeptAsTheImage) {
    const auto bytes = from_hex(vectors::v2);
    const auto datagram = wire::decode_datagram(bytes);
    ASSERT_TRUE(datagram.ok());
    ConsumedExchange exchange(make_plan(15));
    const auto outcome = exchange.on_datagram(*datagram, at(5ms));
    EXPECT_TRUE(outcome.accepted());
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    ASSERT_TRUE(exchange.has_image());
    EXPECT_EQ(to_hex(exchange.image()), "e75a0000b6804760960e0000000000");
    EXPECT_EQ(exchange.last_header().request_id, 108);
    EXPECT_EQ(exchange.last_accepted(), at(5ms));
    EXPECT_EQ(exchange.counters().received, 1u);
    EXPECT_EQ(exchange.counters().accepted, 1u);
    EXPECT_EQ(exchange.counters().missed, 0u);
}

TEST(Vectors, V7OneDataByteLessIsALengthMismatch) {
    auto bytes = from_hex(vectors::v2);
    bytes.pop_back();
    const auto datagram = wire::decode_datagram(bytes);
    ASSERT_TRUE(datagram.ok());
    ConsumedExchange exchange(make_plan(15));
    const auto outcome = exchange.on_datagram(*datagram, at(0ms));
    EXPECT_EQ(outcome.dropped, DropReason::length_mismatch);
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::length_mismatch);
    EXPECT_FALSE(exchange.has_image());
    EXPECT_EQ(exchange.counters().length_mismatches, 1u);
    EXPECT_EQ(exchange.counters().accepted, 0u);
}

TEST(Vectors, V7V5AgainstSignature3_0IsAMismatch) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{3, 0}));
    const auto outcome = feed(exchange, v5_with_data());
    EXPECT_EQ(outcome.dropped, DropReason::signature_mismatch);
    EXPECT_EQ(exchange.state(), ConsumeState::signature_mismatch);
    EXPECT_FALSE(exchange.has_image());
    EXPECT_EQ(exchange.counters().signature_mismatches, 1u);
}

TEST(Vectors, V7V5AgainstSignature2_6IsAMismatch) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 6}));
    const auto outcome = feed(exchange, v5_with_data());
    EXPECT_EQ(outcome.dropped, DropReason::signature_mismatch);
    EXPECT_EQ(exchange.state(), ConsumeState::signature_mismatch);
    EXPECT_EQ(exchange.counters().signature_mismatches, 1u);
}

TEST(Vectors, V5IsAcceptedBySignatures2_5And2_0) {
    for (Signature configured : {Signature{2, 5}, Signature{2, 0}, Signature{0, 0}}) {
        ConsumedExchange exchange(make_plan(15, 3000ms, configured));
        EXPECT_TRUE(feed(exchange, v5_with_data()).accepted()) << to_string(configured);
        EXPECT_EQ(exchange.state(), ConsumeState::ok);
    }
}

TEST(Vectors, V7RequestId65535Then0IsInSequence) {
    ConsumedExchange exchange(make_plan());
    EXPECT_TRUE(feed(exchange, sample(65535)).accepted());
    const auto outcome = feed(exchange, sample(0), 100ms);
    EXPECT_TRUE(outcome.accepted());
    EXPECT_FALSE(outcome.state_changed);
    EXPECT_EQ(exchange.counters().missed, 0u);
    EXPECT_EQ(exchange.counters().accepted, 2u);
    EXPECT_EQ(exchange.last_header().request_id, 0);
}

TEST(ConsumerRules, Rule7AcceptKeepsHeaderAndRestartsTheTimer) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    Sample s = sample(7);
    s.header.time_s = 1695231678;
    s.header.time_ns = 123;
    s.header.status = 0xDEAD;  // recorded, never rejected on
    feed(exchange, sample(6), 0ms);
    EXPECT_EQ(exchange.next_deadline(), at(3000ms));
    EXPECT_TRUE(feed(exchange, s, 2500ms).accepted());
    EXPECT_EQ(exchange.last_header().time_s, 1695231678u);
    EXPECT_EQ(exchange.last_header().time_ns, 123u);
    EXPECT_EQ(exchange.last_header().status, 0xDEADu);
    EXPECT_EQ(exchange.last_accepted(), at(2500ms));
    EXPECT_EQ(exchange.next_deadline(), at(5500ms));
    EXPECT_FALSE(exchange.on_tick(at(3000ms)));
}

TEST(ConsumerRules, Rule8TimeoutMakesTheExchangeStaleOnce) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(1), 1000ms);
    EXPECT_FALSE(exchange.on_tick(at(3999ms)));
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_TRUE(exchange.on_tick(at(4000ms)));
    EXPECT_EQ(exchange.state(), ConsumeState::stale);
    EXPECT_EQ(exchange.counters().timeouts, 1u);
    EXPECT_FALSE(exchange.on_tick(at(9000ms)));
    EXPECT_EQ(exchange.counters().timeouts, 1u);
    EXPECT_EQ(exchange.next_deadline(), std::nullopt);
    EXPECT_TRUE(exchange.has_image());  // the last value stays, with stale quality
}

TEST(ConsumerRules, Rule8FirstSampleAfterStaleRecovers) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(1), 0ms);
    exchange.on_tick(at(3000ms));
    const auto outcome = feed(exchange, sample(2), 3500ms);
    EXPECT_TRUE(outcome.accepted());
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_EQ(exchange.next_deadline(), at(6500ms));
}

TEST(ConsumerRules, Rule8ZeroTimeoutDisables) {
    ConsumedExchange exchange(make_plan(15, 0ms));
    feed(exchange, sample(1), 0ms);
    EXPECT_EQ(exchange.next_deadline(), std::nullopt);
    EXPECT_FALSE(exchange.on_tick(at(24h)));
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
}

TEST(ConsumerRules, Rule8MismatchGoesStaleWhenTheProducerFallsSilent) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(1, 3), 0ms);
    EXPECT_EQ(exchange.next_deadline(), at(3000ms));
    EXPECT_TRUE(exchange.on_tick(at(3000ms)));
    EXPECT_EQ(exchange.state(), ConsumeState::stale);
}

TEST(ConsumerRules, Rule8MismatchStaysWhileMismatchedDatagramsArrive) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    feed(exchange, sample(1, 15, Signature{1, 0}), 0ms);
    feed(exchange, sample(2, 15, Signature{1, 0}), 2000ms);
    EXPECT_FALSE(exchange.on_tick(at(3000ms)));
    EXPECT_EQ(exchange.state(), ConsumeState::signature_mismatch);
    EXPECT_EQ(exchange.next_deadline(), at(5000ms));
}

TEST(ConsumerRules, Rule8StaleThenMismatchIsAStateChange) {
    ConsumedExchange exchange(make_plan(15, 3000ms));
    feed(exchange, sample(1), 0ms);
    exchange.on_tick(at(3000ms));
    const auto outcome = feed(exchange, sample(2, 16), 3100ms);
    EXPECT_EQ(outcome.dropped, DropReason::length_mismatch);
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::length_mismatch);
}

TEST(ConsumedExchange, ReceivedCountsEveryDatagram) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    feed(exchange, sample(10, 15, Signature{2, 5}));  // accepted
    feed(exchange, sample(10, 15, Signature{2, 5}));  // duplicate
    feed(exchange, sample(9, 15, Signature{2, 5}));   // out of order
    feed(exchange, sample(11, 15, Signature{9, 0}));  // signature mismatch
    feed(exchange, sample(12, 14, Signature{2, 5}));  // length mismatch
    feed(exchange, sample(13, 0, Signature{2, 5}));   // no data
    feed(exchange, sample(20, 15, Signature{2, 5}));  // accepted, resynchronised
    const ConsumeCounters& c = exchange.counters();
    EXPECT_EQ(c.received, 7u);
    EXPECT_EQ(c.accepted, 2u);
    EXPECT_EQ(c.duplicates, 1u);
    EXPECT_EQ(c.out_of_order, 1u);
    EXPECT_EQ(c.signature_mismatches, 1u);
    EXPECT_EQ(c.length_mismatches, 1u);
    EXPECT_EQ(c.no_data, 1u);
    EXPECT_EQ(c.missed, 0u);
    EXPECT_EQ(c.timeouts, 0u);
}

TEST(SourceCheck, AnExchangeWithoutSourceAcceptsAnyAddress) {
    ConsumedExchange exchange(make_plan());
    EXPECT_TRUE(exchange.accepts_source(0x0A000001));
    EXPECT_TRUE(exchange.accepts_source(0x7F000001));
    EXPECT_EQ(exchange.counters().wrong_source, 0u);
}

TEST(SourceCheck, AnotherAddressIsRefusedCountedAndLeavesTheExchangeUntouched) {
    auto plan = make_plan();
    plan.spec.source = 0xC0A80101;
    ConsumedExchange exchange(plan);
    EXPECT_FALSE(exchange.accepts_source(0xC0A80102));
    EXPECT_FALSE(exchange.accepts_source(0x7F000001));
    EXPECT_TRUE(exchange.accepts_source(0xC0A80101));
    EXPECT_EQ(exchange.counters().wrong_source, 2u);
    EXPECT_EQ(exchange.counters().received, 0u);
    EXPECT_EQ(exchange.state(), ConsumeState::waiting);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
