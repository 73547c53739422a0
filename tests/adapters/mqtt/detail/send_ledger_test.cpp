// The sender's bookkeeping without a broker: the two windows, the low mark, the client's own
// slots, suspects sent alone after a loss and dropped when lost again, the hold.

#include "adapters/mqtt/detail/send_ledger.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

constexpr std::size_t kCapacity = 1000;

Message message(std::string topic, int qos) {
    Message m;
    m.topic = std::move(topic);
    m.payload = "1";
    m.qos = qos;
    return m;
}

void push(SendLedger& ledger, const std::string& topic, int qos) {
    Message m = message(topic, qos);
    ledger.push(m);
}

struct Sent {
    std::uint64_t id;
    std::string topic;
    bool probe;
};

/// One burst as the sender takes it: take until refused or a suspect, admit each.
std::vector<Sent> burst(SendLedger& ledger) {
    std::vector<Sent> sent;
    Message next;
    bool probe = false;
    while (ledger.take_next(next, probe)) {
        std::string topic = next.topic;
        sent.push_back({ledger.admit(std::move(next), probe), std::move(topic), probe});
        if (probe) break;
    }
    ledger.end_burst();
    return sent;
}

std::vector<std::string> topics(const std::vector<Sent>& sent) {
    std::vector<std::string> out;
    for (const auto& s : sent) out.push_back(s.topic);
    return out;
}

void complete_all(SendLedger& ledger, const std::vector<Sent>& sent) {
    for (const auto& s : sent) {
        ASSERT_TRUE(ledger.complete(s.id));
        ledger.settle(s.id);
    }
}

/// The connection went with `sent` in flight: each is queued again as a suspect; returns the
/// topics of those dropped instead.
std::vector<std::string> lose_connection(SendLedger& ledger) {
    std::vector<std::string> dropped;
    ledger.hold();
    ledger.abandon_in_flight([&](std::uint64_t id, Message&& m) {
        if (auto topic = ledger.requeue_suspect(id, std::move(m)); !topic.empty()) {
            dropped.push_back(std::move(topic));
        }
    });
    return dropped;
}

TEST(SendLedger, AFullWindowWaitsForAnEighthToComplete) {
    SendLedger ledger(kCapacity, kCapacity, false, 16);
    for (int i = 0; i < 40; ++i) push(ledger, "t/" + std::to_string(i), 0);
    ASSERT_TRUE(ledger.ready_to_send());
    std::vector<Sent> sent;
    Message next;
    bool probe = false;
    while (ledger.take_next(next, probe)) {
        sent.push_back({ledger.admit(std::move(next), probe), {}, probe});
    }
    EXPECT_EQ(sent.size(), 16u);
    EXPECT_TRUE(ledger.end_burst());  // full, with more waiting: a backlog
    EXPECT_FALSE(ledger.ready_to_send());
    ASSERT_TRUE(ledger.complete(sent[0].id));
    EXPECT_FALSE(ledger.ready_to_send());  // one free slot is not the low mark
    ASSERT_TRUE(ledger.complete(sent[1].id));
    EXPECT_TRUE(ledger.ready_to_send());
    EXPECT_EQ(burst(ledger).size(), 2u);
    EXPECT_EQ(ledger.pending(), 16u);
    EXPECT_EQ(ledger.queued(), 40u - 18u);
}

TEST(SendLedger, TheAcknowledgedWindowBoundsQoS1Only) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    ledger.set_acknowledged_limit(3);
    for (int i = 0; i < 5; ++i) push(ledger, "q1/" + std::to_string(i), 1);
    const auto first = burst(ledger);
    EXPECT_EQ(topics(first), (std::vector<std::string>{"q1/0", "q1/1", "q1/2"}));
    EXPECT_EQ(ledger.pending_acknowledged(), 3u);
    EXPECT_FALSE(ledger.ready_to_send());
    ASSERT_TRUE(ledger.complete(first[0].id));
    EXPECT_TRUE(ledger.ready_to_send());  // refilled one slot at a time, no low mark
    EXPECT_EQ(topics(burst(ledger)), (std::vector<std::string>{"q1/3"}));

    SendLedger qos0(kCapacity, kCapacity, false, 256);
    qos0.set_acknowledged_limit(1);
    for (int i = 0; i < 5; ++i) push(qos0, "q0/" + std::to_string(i), 0);
    EXPECT_EQ(burst(qos0).size(), 5u);
}

/// Sends one publication per completion, as the sender does once the acknowledged window is
/// full, until `count` went; returns whether the last burst reported a backlog to pack.
bool refill_one_at_a_time(SendLedger& ledger, std::vector<Sent>& in_flight, std::size_t count) {
    bool backlog = false;
    for (std::size_t i = 0; i < count; ++i) {
        EXPECT_TRUE(ledger.complete(in_flight.front().id));
        in_flight.erase(in_flight.begin());
        auto sent = burst(ledger);
        EXPECT_EQ(sent.size(), 1u);
        backlog = ledger.saturated() || ledger.pending() >= ledger.in_flight_limit();
        in_flight.insert(in_flight.end(), sent.begin(), sent.end());
    }
    return backlog;
}

TEST(SendLedger, ABacklogOfPubacksOutlastingEightWindowsSaturatesTheConnection) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    ledger.set_acknowledged_limit(20);
    for (int i = 0; i < 400; ++i) push(ledger, "q1/" + std::to_string(i), 1);
    auto in_flight = burst(ledger);
    ASSERT_EQ(in_flight.size(), 20u);
    // A burst: TCP_NODELAY stays on, and each completion refills its slot at once.
    EXPECT_FALSE(refill_one_at_a_time(ledger, in_flight, 7 * 20));
    EXPECT_FALSE(ledger.saturated());
    // Eight windows later the backlog is the connection's load, not a burst.
    EXPECT_TRUE(refill_one_at_a_time(ledger, in_flight, 20));
    ASSERT_TRUE(ledger.saturated());
    ASSERT_TRUE(ledger.complete(in_flight.front().id));
    EXPECT_FALSE(ledger.ready_to_send());  // saturated: two slots at a time
    ASSERT_TRUE(ledger.complete(in_flight[1].id));
    EXPECT_TRUE(ledger.ready_to_send());
    EXPECT_EQ(burst(ledger).size(), 2u);
    EXPECT_TRUE(ledger.saturated());
}

TEST(SendLedger, ASaturatedConnectionThatCatchesUpSendsEachPublicationAtOnceAgain) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    ledger.set_acknowledged_limit(4);
    for (int i = 0; i < 40; ++i) push(ledger, "q1/" + std::to_string(i), 1);
    auto in_flight = burst(ledger);
    EXPECT_TRUE(refill_one_at_a_time(ledger, in_flight, 8 * 4));
    ASSERT_TRUE(ledger.saturated());
    complete_all(ledger, in_flight);
    EXPECT_EQ(burst(ledger).size(), 4u);  // the last four, and nothing waits after them
    EXPECT_FALSE(ledger.saturated());
}

TEST(SendLedger, ANewConnectionStartsUnsaturated) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    ledger.set_acknowledged_limit(2);
    for (int i = 0; i < 40; ++i) push(ledger, "q1/" + std::to_string(i), 1);
    auto in_flight = burst(ledger);
    EXPECT_TRUE(refill_one_at_a_time(ledger, in_flight, 8 * 2));
    ledger.new_connection();
    EXPECT_FALSE(ledger.saturated());
}

TEST(SendLedger, TheAcknowledgedLimitStaysWithinMaxInFlightAndAboveZero) {
    SendLedger ledger(kCapacity, kCapacity, false, 8);
    EXPECT_EQ(ledger.acknowledged_limit(), 8u);
    ledger.set_acknowledged_limit(65535);
    EXPECT_EQ(ledger.acknowledged_limit(), 8u);
    ledger.set_acknowledged_limit(0);
    EXPECT_EQ(ledger.acknowledged_limit(), 1u);
    SendLedger none(kCapacity, kCapacity, false, 0);
    EXPECT_EQ(none.in_flight_limit(), 1u);
}

TEST(SendLedger, OwnPublicationsTakeAcknowledgedSlotsOfTheirConnectionOnly) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    ledger.set_acknowledged_limit(2);
    ledger.new_connection();
    const auto generation = ledger.reserve_own_slot();  // `online`
    for (int i = 0; i < 3; ++i) push(ledger, "q1/" + std::to_string(i), 1);
    EXPECT_EQ(burst(ledger).size(), 1u);
    EXPECT_FALSE(ledger.ready_to_send());
    EXPECT_TRUE(ledger.own_slots_fit());  // what stop() waits for before `offline`

    ledger.new_connection();  // the broker never answered on the old one
    EXPECT_FALSE(ledger.release_own_slot(generation));
    EXPECT_TRUE(ledger.ready_to_send());
    const auto current = ledger.reserve_own_slot();
    EXPECT_FALSE(ledger.ready_to_send());
    EXPECT_TRUE(ledger.release_own_slot(current));
    EXPECT_FALSE(ledger.release_own_slot(current));  // given back once
    EXPECT_TRUE(ledger.ready_to_send());
}

TEST(SendLedger, AfterALossSuspectsGoAloneFirstThenTheQueue) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    for (const auto* topic : {"a", "b", "c"}) push(ledger, topic, 1);
    EXPECT_EQ(burst(ledger).size(), 3u);
    EXPECT_TRUE(lose_connection(ledger).empty());
    EXPECT_FALSE(ledger.hold());  // once per loss
    push(ledger, "d", 1);
    EXPECT_EQ(ledger.queued(), 4u);
    EXPECT_FALSE(ledger.ready_to_send());  // held until the next connect
    ledger.release_hold();

    std::vector<std::string> order;
    for (int round = 0; round < 4 && ledger.ready_to_send(); ++round) {
        const auto sent = burst(ledger);
        ASSERT_EQ(sent.size(), 1u);
        EXPECT_EQ(sent[0].probe, sent[0].topic != "d");
        EXPECT_FALSE(ledger.ready_to_send());  // nothing beside a suspect in flight
        order.push_back(sent[0].topic);
        complete_all(ledger, sent);
    }
    EXPECT_EQ(order, (std::vector<std::string>{"a", "b", "c", "d"}));
    EXPECT_FALSE(ledger.has_queued());
}

TEST(SendLedger, ASuspectWaitsUntilNothingIsInFlight) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    push(ledger, "a", 1);
    push(ledger, "b", 1);
    const auto sent = burst(ledger);
    ASSERT_EQ(topics(sent), (std::vector<std::string>{"a", "b"}));
    // `a` failed the way a loss makes it fail, yet the connection survived the hold.
    auto a = ledger.complete(sent[0].id);
    ASSERT_TRUE(a);
    EXPECT_TRUE(ledger.hold());
    EXPECT_TRUE(ledger.requeue_suspect(sent[0].id, std::move(*a)).empty());
    ledger.release_hold();
    push(ledger, "c", 1);
    EXPECT_FALSE(ledger.ready_to_send());  // `b` is in flight
    complete_all(ledger, {sent[1]});
    const auto retry = burst(ledger);
    ASSERT_EQ(retry.size(), 1u);
    EXPECT_EQ(retry[0].topic, "a");
    EXPECT_TRUE(retry[0].probe);
}

TEST(SendLedger, ASuspectLostAgainWhileAloneIsDropped) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    push(ledger, "poison", 1);
    push(ledger, "next", 1);
    burst(ledger);
    EXPECT_TRUE(lose_connection(ledger).empty());  // both suspects now
    ledger.release_hold();
    const auto alone = burst(ledger);
    ASSERT_EQ(topics(alone), (std::vector<std::string>{"poison"}));
    EXPECT_EQ(lose_connection(ledger), (std::vector<std::string>{"poison"}));
    ledger.release_hold();
    const auto after = burst(ledger);
    ASSERT_EQ(topics(after), (std::vector<std::string>{"next"}));
    EXPECT_TRUE(after[0].probe);  // still a suspect of the first loss
    complete_all(ledger, after);
    EXPECT_FALSE(ledger.has_queued());
}

TEST(SendLedger, APublicationThatNeverLeftGoesAgainAsWhatItWas) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    push(ledger, "a", 1);
    burst(ledger);
    lose_connection(ledger);
    ledger.release_hold();
    const auto probe = burst(ledger);
    ASSERT_EQ(probe.size(), 1u);
    // Paho refused the suspect at once, disconnected: it proved nothing, and stays a suspect.
    ledger.requeue_unsent(probe[0].id, std::move(*ledger.complete(probe[0].id)));
    push(ledger, "b", 1);
    const auto again = burst(ledger);
    ASSERT_EQ(topics(again), (std::vector<std::string>{"a"}));
    EXPECT_TRUE(again[0].probe);
    complete_all(ledger, again);

    // One that was no suspect is sent again first, with the others.
    push(ledger, "c", 1);
    const auto both = burst(ledger);
    ASSERT_EQ(topics(both), (std::vector<std::string>{"b", "c"}));
    ledger.requeue_unsent(both[1].id, std::move(*ledger.complete(both[1].id)));
    complete_all(ledger, {both[0]});
    push(ledger, "d", 1);
    const auto resent = burst(ledger);
    EXPECT_EQ(topics(resent), (std::vector<std::string>{"c", "d"}));
    EXPECT_FALSE(resent[0].probe);
}

TEST(SendLedger, CompletionsOfAbandonedPublicationsAreIgnored) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    push(ledger, "q0", 0);
    const auto sent = burst(ledger);
    std::vector<std::uint64_t> abandoned;
    ledger.abandon_in_flight([&](std::uint64_t id, Message&&) { abandoned.push_back(id); });
    EXPECT_EQ(abandoned, (std::vector<std::uint64_t>{sent[0].id}));
    EXPECT_FALSE(ledger.complete(sent[0].id));
    EXPECT_EQ(ledger.pending(), 0u);
}

TEST(SendLedger, DiscardingDropsTheQueueAndTheRetries) {
    SendLedger ledger(kCapacity, kCapacity, false, 256);
    push(ledger, "a", 1);
    burst(ledger);
    lose_connection(ledger);
    push(ledger, "b", 1);
    push(ledger, "c", 0);
    EXPECT_EQ(ledger.discard_queued(), 3u);
    EXPECT_FALSE(ledger.has_queued());
    EXPECT_EQ(ledger.queued(), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
