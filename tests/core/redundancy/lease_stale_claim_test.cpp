// The lease against claims made by a unit that could not hear the leader (core/redundancy/
// lease.hpp, the beat and what a claim heard): cut off from the broker, its claims sit in a
// buffer and arrive once the path is back, in any order with the leader's renewals.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "eip2mqtt/core/redundancy/lease.hpp"

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0{std::chrono::hours(1)};

LeaseSettings settings(std::string id, int priority = 0) {
    return {std::move(id), priority, 2000ms, 100ms};
}

/// The broker took `claim`, made at `at`: it acknowledges it, and the unit hears it back.
void claim_taken(Lease& lease, const std::optional<LeaderRecord>& claim, MonoTime at) {
    ASSERT_TRUE(claim.has_value());
    lease.on_acknowledged(at);
    lease.on_record(*claim, at);
}

/// "a" leads from 2 s (claimed at 1.5 s), renewing every 500 ms, each acknowledged at once,
/// up to `until`; "b" heard it up to `heard_until` (the renewals sent before), then nothing.
struct Pair {
    Lease a{settings("a"), t0};
    Lease b;
    std::vector<LeaderRecord> sent;  ///< a's records, in order

    Pair(int b_priority, MonoTime heard_until, MonoTime until) : b(settings("b", b_priority), t0) {
        b.on_connection(true, t0);
        // b hears a's claim at once, so it does not claim at 1.5 s itself.
        for (auto at = t0 + 1500ms; at <= until; at += 500ms) {
            auto record = a.tick(at);
            claim_taken(a, record, at);
            if (at <= heard_until) b.on_record(*record, at);
            sent.push_back(*record);
        }
        EXPECT_EQ(a.role(until), Role::leader);
    }
};

TEST(LeaseStaleClaimTest, AClaimCarriesItsBeatAndTheRecordItsClaimantLastHeard) {
    Pair pair(0, t0 + 2500ms, t0 + 2500ms);
    const auto claim = pair.b.tick(t0 + 4000ms);
    ASSERT_TRUE(claim.has_value());
    EXPECT_TRUE(claim->claim);
    EXPECT_EQ(claim->epoch, 2u);
    EXPECT_GT(claim->beat, pair.sent.back().beat);
    ASSERT_TRUE(claim->heard.has_value());
    EXPECT_EQ(*claim->heard, (LeaderMark{"a", 1, pair.sent.back().beat}));
    EXPECT_GT(pair.sent.back().beat, pair.sent.front().beat);
}

TEST(LeaseStaleClaimTest, ALiveLeaderIgnoresAClaimDeliveredAfterItsRenewalsWhateverTheOrder) {
    // b hears nothing after 2.5 s and claims epoch 2 at 4 s; a renews on until 8 s. The
    // claim reaches a at any instant from then on: before, between and after renewals.
    for (auto delivered_at = t0 + 4000ms; delivered_at <= t0 + 7500ms; delivered_at += 125ms) {
        Pair pair(0, t0 + 2500ms, t0 + 4000ms);
        const auto claim = pair.b.tick(t0 + 4000ms);
        ASSERT_TRUE(claim.has_value());
        std::optional<LeaderRecord> reasserted;
        bool delivered = false;
        const auto deliver = [&] {
            pair.a.on_record(*claim, delivered_at);
            EXPECT_EQ(pair.a.role(delivered_at), Role::leader) << delivered_at - t0;
            reasserted = pair.a.tick(delivered_at);
            delivered = true;
        };
        for (auto at = t0 + 4500ms; at < t0 + 8000ms; at += 500ms) {
            if (!delivered && delivered_at < at) deliver();  // between two renewals
            const auto renewal = pair.a.tick(at);
            // Between a renewal's sending and its acknowledgement.
            if (!delivered && delivered_at == at) deliver();
            if (renewal) pair.a.on_acknowledged(at);
            if (reasserted) pair.a.on_acknowledged(delivered_at);
            EXPECT_EQ(pair.a.role(at), Role::leader);
        }
        // It renewed at once under the claim's epoch, as a confirmed leader.
        ASSERT_TRUE(reasserted.has_value());
        EXPECT_EQ(reasserted->epoch, 2u);
        EXPECT_FALSE(reasserted->claim);
        EXPECT_EQ(pair.a.epoch(), 2u);
    }
}

TEST(LeaseStaleClaimTest, AnAcknowledgementAloneLeadsNobodyBeforeTheRenewalsQueuedAheadOfIt) {
    // b outranks a; its claim, made cut off at 4 s, is acknowledged at 4.6 s, before the
    // renewals of a the broker queued for b meanwhile (it holds those beyond b's in-flight
    // window, and sends an acknowledgement at once): b does not lead on it.
    Pair pair(9, t0 + 2500ms, t0 + 4500ms);
    const auto claim = pair.b.tick(t0 + 4000ms);
    ASSERT_TRUE(claim.has_value());
    pair.b.on_acknowledged(t0 + 4000ms);
    pair.b.tick(t0 + 4600ms);
    EXPECT_EQ(pair.b.role(t0 + 4600ms), Role::standby);
    // Then the renewals b never heard (sent from 3 s on), then its claim heard back: it gave
    // way to the first of them, a renewal after the one its claim named.
    for (std::size_t i = 3; i < pair.sent.size(); ++i) pair.b.on_record(pair.sent[i], t0 + 4610ms);
    pair.b.on_record(*claim, t0 + 4620ms);
    pair.b.tick(t0 + 5200ms);
    EXPECT_EQ(pair.b.role(t0 + 5200ms), Role::standby);
    EXPECT_EQ(pair.b.leader_id(), "a");
    EXPECT_FALSE(pair.b.may_produce(t0 + 5200ms));
}

TEST(LeaseStaleClaimTest, ARenewalTheBrokerTookAfterTheClaimDoesNotUndoIt) {
    // a's renewals from 3 s on were held on a's way to the broker (a was fenced meanwhile),
    // and reached it after b's claim, made at 4 s: b hears its claim back first, then them.
    Pair pair(0, t0 + 2500ms, t0 + 4500ms);
    const auto claim = pair.b.tick(t0 + 4000ms);
    claim_taken(pair.b, claim, t0 + 4000ms);
    for (std::size_t i = 3; i < pair.sent.size(); ++i) pair.b.on_record(pair.sent[i], t0 + 4100ms);
    pair.b.tick(t0 + 4500ms);
    EXPECT_EQ(pair.b.role(t0 + 4500ms), Role::leader);
}

TEST(LeaseStaleClaimTest, TheClaimantGivesWayToTheRenewalEvenIfItLedMeanwhileAndOutranks) {
    // b outranks a; its claim, made cut off at 4 s, is acknowledged and heard back at 4.6 s,
    // ahead of a's renewals (delayed on a's side): it leads at once.
    Pair pair(9, t0 + 2500ms, t0 + 4500ms);
    const auto claim = pair.b.tick(t0 + 4000ms);
    claim_taken(pair.b, claim, t0 + 4000ms);
    pair.b.tick(t0 + 4600ms);
    ASSERT_EQ(pair.b.role(t0 + 4600ms), Role::leader);
    // a hears the claim, renews over it; b hears that renewal of its own epoch.
    pair.a.on_record(*claim, t0 + 4600ms);
    const auto renewal = pair.a.tick(t0 + 4600ms);
    ASSERT_TRUE(renewal.has_value());
    pair.b.on_record(*renewal, t0 + 4610ms);
    EXPECT_EQ(pair.b.role(t0 + 4610ms), Role::standby);
    EXPECT_EQ(pair.b.leader_id(), "a");
    EXPECT_FALSE(pair.b.may_produce(t0 + 4610ms));
    pair.a.on_acknowledged(t0 + 4600ms);
    EXPECT_EQ(pair.a.role(t0 + 4610ms), Role::leader);
}

TEST(LeaseStaleClaimTest, AClaimThatHeardTheNewestAcknowledgedRenewalIsNotStale) {
    // The leader's own view only: such a claim follows the rules as before (a newer epoch).
    Pair pair(0, t0 + 4500ms, t0 + 4500ms);
    LeaderRecord claim{"b", 2, 0, true};
    claim.heard = LeaderMark{"a", 1, pair.sent.back().beat};
    pair.a.on_record(claim, t0 + 4600ms);
    EXPECT_EQ(pair.a.role(t0 + 4600ms), Role::standby);
    EXPECT_EQ(pair.a.leader_id(), "b");
}

TEST(LeaseStaleClaimTest, AClaimThatNamesNothingCannotDeposeALiveLeader) {
    // A claim of an earlier version, or of a unit that never heard anyone.
    Pair pair(0, t0, t0 + 3000ms);
    pair.a.on_record(LeaderRecord{"b", 5, 0, true}, t0 + 3100ms);
    EXPECT_EQ(pair.a.role(t0 + 3100ms), Role::leader);
    const auto renewal = pair.a.tick(t0 + 3100ms);
    ASSERT_TRUE(renewal.has_value());
    EXPECT_EQ(renewal->epoch, 5u);
}

TEST(LeaseStaleClaimTest, AUnitWhoseClaimWasNeverAcknowledgedClaimsNoMoreUntilItIs) {
    Lease lease(settings("b"), t0);
    ASSERT_TRUE(lease.tick(t0 + 1500ms).has_value());
    // Cut off: nothing acknowledged, nothing heard. It lapses at 2.75 s, and claims no more.
    for (auto at = t0 + 2000ms; at < t0 + 20s; at += 100ms) {
        const auto record = lease.tick(at);
        EXPECT_TRUE(!record || at < t0 + 2750ms) << at - t0;
    }
    EXPECT_EQ(lease.epoch(), 1u);
    EXPECT_EQ(lease.writes(t0 + 20s), WritePolicy::leave_to_leader);
    // The path is back: it waits T - R from then, to hear who leads.
    lease.on_acknowledged(t0 + 2500ms);  // the last one sent, at its renewal interval
    EXPECT_FALSE(lease.tick(t0 + 20s).has_value());
    EXPECT_FALSE(lease.tick(t0 + 21499ms).has_value());
    const auto again = lease.tick(t0 + 21500ms);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->epoch, 2u);
}

TEST(LeaseStaleClaimTest, ANewConnectionClearsAClaimNeverAcknowledged) {
    Lease lease(settings("b"), t0);
    ASSERT_TRUE(lease.tick(t0 + 1500ms).has_value());
    lease.tick(t0 + 2750ms);
    lease.on_connection(false, t0 + 5s);
    lease.on_connection(true, t0 + 6s);
    EXPECT_FALSE(lease.tick(t0 + 7499ms).has_value());
    EXPECT_TRUE(lease.tick(t0 + 7500ms).has_value());
}

TEST(LeaseStaleClaimTest, ADisconnectedUnitDoesNotClaim) {
    Lease lease(settings("b"), t0);
    lease.on_connection(false, t0);
    for (auto at = t0; at < t0 + 20s; at += 100ms) EXPECT_FALSE(lease.tick(at).has_value());
    EXPECT_EQ(lease.epoch(), 0u);
    // Connected: T - R after, as from a start.
    lease.on_connection(true, t0 + 20s);
    EXPECT_FALSE(lease.tick(t0 + 21499ms).has_value());
    EXPECT_TRUE(lease.tick(t0 + 21500ms).has_value());
}

TEST(LeaseStaleClaimTest, AStandbyFollowsItsLeaderRenewingBelowTheEpochItsFailedClaimRaised) {
    Pair pair(0, t0 + 2500ms, t0 + 5500ms);
    ASSERT_TRUE(pair.b.tick(t0 + 4000ms).has_value());  // epoch 2, never delivered
    pair.b.tick(t0 + 5250ms);                           // lapsed
    // The path back: a's renewals of epoch 1, sent after what b heard, reach it.
    for (auto at = t0 + 6000ms; at < t0 + 20s; at += 500ms) {
        const auto renewal = pair.a.tick(at);
        ASSERT_TRUE(renewal.has_value());
        pair.a.on_acknowledged(at);
        EXPECT_TRUE(pair.b.on_record(*renewal, at)) << at - t0;  // followed: its watermarks
        EXPECT_FALSE(pair.b.tick(at + 1ms).has_value()) << at - t0;
        EXPECT_EQ(pair.b.leader_id(), "a");
        EXPECT_EQ(pair.b.writes(at + 1ms), WritePolicy::leave_to_leader);
    }
    EXPECT_EQ(pair.a.role(t0 + 20s), Role::leader);
}

TEST(LeaseTest, RenewedSinceLeadingOnlyOnceARenewalSentAsItLeadsIsAcknowledged) {
    Lease lease(settings("a"), t0);
    claim_taken(lease, lease.tick(t0 + 1500ms), t0 + 1500ms);
    EXPECT_FALSE(lease.renewed_since_leading(t0 + 1600ms));
    ASSERT_TRUE(lease.tick(t0 + 2000ms).has_value());  // leads, and renews
    EXPECT_EQ(lease.role(t0 + 2000ms), Role::leader);
    EXPECT_FALSE(lease.renewed_since_leading(t0 + 2000ms));
    lease.on_acknowledged(t0 + 2000ms);
    EXPECT_TRUE(lease.renewed_since_leading(t0 + 2010ms));
    // Fenced: no more.
    EXPECT_FALSE(lease.renewed_since_leading(t0 + 3250ms));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
