// ConsumedExchange, docs/protocol.md §4 rules 4 and 5: a datagram of another signature or length.

#include <gtest/gtest.h>

#include <vector>

#include "tests/core/exchange/consumed_exchange_samples.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::exchange {
namespace EIP2MQTT_THIS_FILE {

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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::exchange
