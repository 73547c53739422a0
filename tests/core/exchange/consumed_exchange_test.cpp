#include "eip2mqtt/core/exchange/consumed_exchange.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {
namespace {

using namespace std::chrono_literals;
using test::from_hex;
using test::to_hex;
using wire::DropReason;
using wire::Signature;
namespace vectors = test::vectors;

MonoTime at(std::chrono::milliseconds offset) { return MonoTime{} + offset; }

plan::ExchangePlan make_plan(std::uint16_t length = 15, std::chrono::milliseconds timeout = 3000ms,
                             Signature signature = {}) {
    plan::ExchangePlan plan;
    plan.spec.name = "test";
    plan.spec.producer_id = wire::ProducerId{0xC0A80101};
    plan.spec.exchange_id = 1;
    plan.spec.signature = signature;
    plan.length = length;
    plan.timeout = timeout;
    return plan;
}

/// A datagram of the exchange with owned data.
struct Sample {
    wire::Header header;
    std::vector<std::byte> data;

    wire::Datagram datagram() const { return {header, data}; }
};

Sample sample(std::uint16_t request_id, std::size_t size = 15, Signature signature = {},
              std::byte fill = std::byte{0x11}) {
    Sample s;
    s.header.request_id = request_id;
    s.header.producer_id = wire::ProducerId{0xC0A80101};
    s.header.exchange_id = 1;
    s.header.signature = signature.to_wire();
    s.data.assign(size, fill);
    return s;
}

/// Datagram with V5's header (signature 2.5) and `size` data bytes: V5 itself has none.
Sample v5_with_data(std::size_t size = 15) {
    Sample s;
    s.header = wire::decode_header(from_hex(vectors::v5));
    s.data.assign(size, std::byte{0x42});
    return s;
}

ConsumeOutcome feed(ConsumedExchange& exchange, const Sample& s,
                    std::chrono::milliseconds when = 0ms) {
    return exchange.on_datagram(s.datagram(), at(when));
}

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

TEST(ConsumerRules, Rule4ConfiguredSignatureWithUnsetReceivedIsConsumed) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_TRUE(feed(exchange, sample(1, 15, Signature{})).accepted());
}

TEST(ConsumerRules, Rule4MinorOnlySignatureIsChecked) {
    // 0.3 is a set signature (low 16 bits non-zero): major 0 must match, minor >= 3.
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{0, 3}));
    EXPECT_EQ(feed(exchange, sample(1, 15, Signature{1, 3})).dropped,
              DropReason::signature_mismatch);
    EXPECT_EQ(feed(exchange, sample(2, 15, Signature{0, 2})).dropped,
              DropReason::signature_mismatch);
    EXPECT_TRUE(feed(exchange, sample(3, 15, Signature{0, 4})).accepted());
}

TEST(ConsumerRules, Rule4MismatchKeepsThePreviousImage) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    ASSERT_TRUE(feed(exchange, sample(10, 15, Signature{2, 5}, std::byte{0x01})).accepted());
    const auto outcome = feed(exchange, sample(11, 15, Signature{3, 5}, std::byte{0x02}), 10ms);
    EXPECT_EQ(outcome.dropped, DropReason::signature_mismatch);
    EXPECT_TRUE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::signature_mismatch);
    EXPECT_EQ(to_hex(exchange.image()), "010101010101010101010101010101");
    EXPECT_EQ(exchange.last_header().request_id, 10);
    EXPECT_EQ(exchange.last_accepted(), at(0ms));
}

TEST(ConsumerRules, Rule4RepeatedMismatchIsNoStateChange) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_TRUE(feed(exchange, sample(1, 15, Signature{1, 0})).state_changed);
    const auto outcome = feed(exchange, sample(2, 15, Signature{1, 0}));
    EXPECT_EQ(outcome.dropped, DropReason::signature_mismatch);
    EXPECT_FALSE(outcome.state_changed);
    EXPECT_EQ(exchange.counters().signature_mismatches, 2u);
}

TEST(ConsumerRules, Rule4IsCheckedBeforeRule5) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_EQ(feed(exchange, sample(1, 3, Signature{3, 0})).dropped,
              DropReason::signature_mismatch);
    EXPECT_EQ(exchange.counters().length_mismatches, 0u);
}

TEST(ConsumerRules, Rule5LongerDataIsALengthMismatch) {
    ConsumedExchange exchange(make_plan(15));
    EXPECT_EQ(feed(exchange, sample(1, 16)).dropped, DropReason::length_mismatch);
    EXPECT_EQ(exchange.state(), ConsumeState::length_mismatch);
}

TEST(ConsumerRules, Rule5EmptyDataIsDroppedWithoutStateChange) {
    ConsumedExchange exchange(make_plan(15));
    ASSERT_TRUE(feed(exchange, sample(1)).accepted());
    const auto outcome = feed(exchange, sample(2, 0));
    EXPECT_EQ(outcome.dropped, DropReason::no_data);
    EXPECT_FALSE(outcome.state_changed);
    EXPECT_EQ(exchange.state(), ConsumeState::ok);
    EXPECT_EQ(exchange.counters().no_data, 1u);
}

TEST(ConsumerRules, Rule5NewerMinorMayAppendData) {
    ConsumedExchange exchange(make_plan(4, 3000ms, Signature{2, 5}));
    Sample s = sample(1, 6, Signature{2, 6});
    s.data = from_hex("0102030405ff");
    const auto outcome = feed(exchange, s);
    EXPECT_TRUE(outcome.accepted());
    EXPECT_EQ(to_hex(exchange.image()), "01020304");
}

TEST(ConsumerRules, Rule5SameMinorMayNotAppendData) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_EQ(feed(exchange, sample(1, 20, Signature{2, 5})).dropped, DropReason::length_mismatch);
}

TEST(ConsumerRules, Rule5NewerMinorMayNotShortenData) {
    ConsumedExchange exchange(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_EQ(feed(exchange, sample(1, 14, Signature{2, 6})).dropped, DropReason::length_mismatch);
}

TEST(ConsumerRules, Rule5WithoutSignaturesDataMayNotGrow) {
    ConsumedExchange unset(make_plan(15));
    EXPECT_EQ(feed(unset, sample(1, 20, Signature{2, 6})).dropped, DropReason::length_mismatch);
    ConsumedExchange unset_received(make_plan(15, 3000ms, Signature{2, 5}));
    EXPECT_EQ(feed(unset_received, sample(1, 20)).dropped, DropReason::length_mismatch);
}

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

}  // namespace
}  // namespace eip2mqtt::core::exchange
