#include "eip2mqtt/core/redundancy/lease.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const MonoTime t0{std::chrono::hours(1)};

LeaseSettings settings(std::string id, int priority = 0, std::chrono::milliseconds period = 100ms) {
    return {std::move(id), priority, 2000ms, period};
}

LeaderRecord record(std::string id, std::uint64_t epoch, int priority = 0) {
    return {std::move(id), epoch, priority};
}

LeaderRecord claim_of(std::string id, std::uint64_t epoch) {
    return {std::move(id), epoch, 0, true};
}

/// The broker took `claim`, made at `at`: it acknowledges it, and the unit hears it back.
void claim_taken(Lease& lease, const std::optional<LeaderRecord>& claim, MonoTime at) {
    ASSERT_TRUE(claim.has_value());
    lease.on_acknowledged(at);
    lease.on_record(*claim, at);
}

/// A unit that claimed at `at` (nobody heard since its start at t0) and had its claim
/// acknowledged: the leader once a renewal interval passed.
Lease leader_from(MonoTime at, std::string id = "a") {
    Lease lease(settings(std::move(id)), t0);
    claim_taken(lease, lease.tick(at), at);
    EXPECT_FALSE(lease.tick(at + 500ms - 1ms).has_value());
    EXPECT_TRUE(lease.tick(at + 500ms).has_value());
    lease.on_acknowledged(at + 500ms);
    return lease;
}

TEST(LeaseTest, AStandbyClaimsARenewalIntervalBeforeTheTakeoverWithEpochOne) {
    Lease lease(settings("a"), t0);
    EXPECT_FALSE(lease.tick(t0 + 1499ms).has_value());
    EXPECT_EQ(lease.role(t0 + 1499ms), Role::standby);
    const auto claim = lease.tick(t0 + 1500ms);
    ASSERT_TRUE(claim.has_value());
    EXPECT_EQ(*claim, claim_of("a", 1));
    // Claiming is not leading.
    EXPECT_EQ(lease.role(t0 + 1500ms), Role::standby);
    EXPECT_FALSE(lease.may_produce(t0 + 1500ms));
}

TEST(LeaseTest, AClaimLeadsOnceAcknowledgedAndARenewalIntervalPassedATakeoverAfterTheStart) {
    Lease lease(settings("a"), t0);
    claim_taken(lease, lease.tick(t0 + 1500ms), t0 + 1500ms);
    EXPECT_FALSE(lease.tick(t0 + 1999ms).has_value());
    EXPECT_EQ(lease.role(t0 + 1999ms), Role::standby);
    EXPECT_TRUE(lease.tick(t0 + 2000ms).has_value());
    EXPECT_EQ(lease.role(t0 + 2000ms), Role::leader);
}

TEST(LeaseTest, AnUnacknowledgedClaimNeverLeadsAndFallsBackToStandby) {
    Lease lease(settings("a"), t0);
    ASSERT_TRUE(lease.tick(t0 + 2s).has_value());
    EXPECT_TRUE(lease.tick(t0 + 2500ms).has_value());  // a renewal of the claim
    EXPECT_EQ(lease.role(t0 + 2500ms), Role::standby);
    // T - 3R/2 after the claim it gives up. It claims again only once its last claim was
    // acknowledged (the path is back: lease_stale_claim_test.cpp), T - R after that.
    lease.tick(t0 + 2s + 1250ms);
    EXPECT_FALSE(lease.tick(t0 + 2s + 1250ms + 1500ms).has_value());
    lease.on_acknowledged(t0 + 2500ms);
    lease.tick(t0 + 5s);
    EXPECT_FALSE(lease.tick(t0 + 6499ms).has_value());
    const auto again = lease.tick(t0 + 6500ms);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->epoch, 2u);
}

TEST(LeaseTest, TheLeaderRenewsEveryQuarterOfTheTakeover) {
    auto lease = leader_from(t0 + 2s);
    EXPECT_EQ(lease.renew_interval(), 500ms);
    EXPECT_FALSE(lease.tick(t0 + 2999ms).has_value());
    const auto renewal = lease.tick(t0 + 3000ms);
    ASSERT_TRUE(renewal.has_value());
    EXPECT_EQ(*renewal, record("a", 1));
    EXPECT_FALSE(lease.tick(t0 + 3499ms).has_value());
    EXPECT_TRUE(lease.tick(t0 + 3500ms).has_value());
}

TEST(LeaseTest, ALeaderFencesItselfBeforeTheTakeoverWhenNoRenewalIsAcknowledged) {
    auto lease = leader_from(t0 + 2s);
    // Last acknowledged renewal sent at t0 + 2.5 s; nothing acknowledged since.
    const auto last = t0 + 2500ms;
    EXPECT_EQ(lease.role(last + 1249ms), Role::leader);
    EXPECT_TRUE(lease.fenced(last + 1250ms));
    EXPECT_EQ(lease.role(last + 1250ms), Role::standby);
    EXPECT_FALSE(lease.may_produce(last + 1250ms));
    // Not taken, not refused: the standby that takes over answers them.
    EXPECT_EQ(lease.writes(last + 1250ms), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, LeadingUntilIsTheInstantTheLeaseLapsesAndMovesWithEachAcknowledgement) {
    Lease standby(settings("a"), t0);
    EXPECT_FALSE(standby.leading_until().has_value());
    auto lease = leader_from(t0 + 2s);
    // Last acknowledged renewal sent at t0 + 2.5 s: fenced from 1.25 s later, as role() says.
    EXPECT_EQ(lease.leading_until(), t0 + 3750ms);
    EXPECT_EQ(lease.role(*lease.leading_until() - 1ms), Role::leader);
    EXPECT_EQ(lease.role(*lease.leading_until()), Role::standby);
    claim_taken(lease, lease.tick(t0 + 3s), t0 + 3s);
    EXPECT_EQ(lease.leading_until(), t0 + 4250ms);
    lease.tick(t0 + 4250ms);  // stepped down
    EXPECT_FALSE(lease.leading_until().has_value());
}

TEST(LeaseTest, AResumedLeaderIsFencedAtItsFirstQuestionWithoutATick) {
    auto lease = leader_from(t0 + 2s);
    // SIGSTOP for ten seconds: no tick ran, the first question after it already says no.
    EXPECT_FALSE(lease.may_produce(t0 + 12s));
    EXPECT_EQ(lease.role(t0 + 12s), Role::standby);
    // Its tick steps it down: it waits T - R before it claims again.
    EXPECT_FALSE(lease.tick(t0 + 12s).has_value());
    EXPECT_EQ(lease.writes(t0 + 12s), WritePolicy::leave_to_leader);
    EXPECT_FALSE(lease.tick(t0 + 13499ms).has_value());
    EXPECT_TRUE(lease.tick(t0 + 13500ms).has_value());
}

TEST(LeaseTest, TheFenceComesHalfARenewalBeforeTheClaimOfAStandbyThatLeadsATakeoverLater) {
    auto leader = leader_from(t0 + 2s, "a");
    Lease standby(settings("b"), t0);
    // The renewal sent at 2.5 s reaches the standby at 2.5 s (no delay at all: the worst case).
    const auto heard = t0 + 2500ms;
    standby.on_record(record("a", 1), heard);
    const auto fence = heard + 1250ms;
    EXPECT_TRUE(leader.fenced(fence));
    EXPECT_FALSE(standby.tick(fence).has_value());
    EXPECT_FALSE(standby.tick(heard + 1499ms).has_value());
    const auto claim = standby.tick(heard + 1500ms);
    ASSERT_TRUE(claim.has_value());
    EXPECT_EQ(*claim, claim_of("b", 2));
    claim_taken(standby, claim, heard + 1500ms);
    standby.tick(heard + 1999ms);
    EXPECT_EQ(standby.role(heard + 1999ms), Role::standby);
    standby.tick(heard + 2000ms);
    EXPECT_EQ(standby.role(heard + 2000ms), Role::leader);
    // Its period (100 ms) is shorter than the margin of the fence: it produces as it leads.
    EXPECT_TRUE(standby.may_produce(heard + 2000ms));
}

TEST(LeaseTest, AcknowledgedRenewalsKeepTheLeaderUnfenced) {
    auto lease = leader_from(t0 + 2s);
    for (auto at = t0 + 3s; at < t0 + 20s; at += 500ms) {
        claim_taken(lease, lease.tick(at), at);
        EXPECT_EQ(lease.role(at + 499ms), Role::leader);
    }
}

TEST(LeaseTest, ANewLeaderProducesOnlyAPeriodAfterTheLatestFenceOfTheLeaderItHeard) {
    Lease lease(settings("b", 0, 1500ms), t0);
    // Nobody heard since the start: as if a leader had renewed then, fenced at the latest
    // T - 3R/2 later (1.25 s); its last datagram then was a period (1.5 s) behind at 2.75 s.
    claim_taken(lease, lease.tick(t0 + 1500ms), t0 + 1500ms);
    lease.tick(t0 + 2000ms);
    lease.on_acknowledged(t0 + 2000ms);
    EXPECT_EQ(lease.role(t0 + 2000ms), Role::leader);
    EXPECT_FALSE(lease.may_produce(t0 + 2749ms));
    EXPECT_TRUE(lease.may_produce(t0 + 2750ms));
}

TEST(LeaseTest, AShortPeriodStillWaitsForTheClaimToStand) {
    Lease lease(settings("b", 0, 10ms), t0);
    claim_taken(lease, lease.tick(t0 + 1500ms), t0 + 1500ms);
    EXPECT_FALSE(lease.may_produce(t0 + 1999ms));
    lease.tick(t0 + 2000ms);
    EXPECT_TRUE(lease.may_produce(t0 + 2000ms));
}

TEST(LeaseTest, ALeaderSeeingANewerEpochStepsDown) {
    auto lease = leader_from(t0 + 2s, "a");
    lease.on_record(record("b", 2), t0 + 2600ms);
    EXPECT_EQ(lease.role(t0 + 2600ms), Role::standby);
    EXPECT_FALSE(lease.may_produce(t0 + 2600ms));
    EXPECT_EQ(lease.epoch(), 2u);
    EXPECT_EQ(lease.leader_id(), "b");
    EXPECT_FALSE(lease.tick(t0 + 3s).has_value());  // no renewal any more
    EXPECT_EQ(lease.writes(t0 + 3s), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, AStaleRecordOfAnOlderEpochChangesNothing) {
    auto lease = leader_from(t0 + 2s, "a");
    lease.on_record(record("b", 0, 9), t0 + 2600ms);
    EXPECT_EQ(lease.role(t0 + 2600ms), Role::leader);
}

TEST(LeaseTest, SimultaneousClaimsAreWonByTheHigherPriority) {
    Lease low(settings("z", 1), t0);
    Lease high(LeaseSettings{"a", 7, 2000ms, 100ms}, t0);
    const auto low_claim = low.tick(t0 + 2s);
    const auto high_claim = high.tick(t0 + 2s);
    ASSERT_TRUE(low_claim && high_claim);
    EXPECT_EQ(low_claim->epoch, high_claim->epoch);
    low.on_acknowledged(t0 + 2s);
    high.on_acknowledged(t0 + 2s);
    // Each sees both claims, in the broker's order.
    for (auto* lease : {&low, &high}) {
        lease->on_record(*low_claim, t0 + 2010ms);
        lease->on_record(*high_claim, t0 + 2010ms);
    }
    low.tick(t0 + 2500ms);
    high.tick(t0 + 2500ms);
    EXPECT_EQ(low.role(t0 + 2500ms), Role::standby);
    EXPECT_EQ(high.role(t0 + 2500ms), Role::leader);
    EXPECT_EQ(low.leader_id(), "a");
}

TEST(LeaseTest, SimultaneousClaimsOfEqualPriorityAreWonByTheHigherId) {
    Lease a(settings("gw-a"), t0);
    Lease b(settings("gw-b"), t0);
    const auto claim_a = a.tick(t0 + 2s);
    const auto claim_b = b.tick(t0 + 2s);
    claim_taken(a, claim_a, t0 + 2s);
    claim_taken(b, claim_b, t0 + 2s);
    a.on_record(*claim_b, t0 + 2010ms);
    b.on_record(*claim_a, t0 + 2010ms);
    a.tick(t0 + 2500ms);
    b.tick(t0 + 2500ms);
    EXPECT_EQ(a.role(t0 + 2500ms), Role::standby);
    EXPECT_EQ(b.role(t0 + 2500ms), Role::leader);
}

TEST(LeaseTest, ALateClaimOfTheLeadersEpochGivesWayToItsRenewals) {
    // "z" outranks "a", but claimed epoch 1 cut off from the broker, which delivered the claim
    // only once the path was back, after "a" had confirmed its own claim of epoch 1.
    auto a = leader_from(t0 + 2s, "a");
    Lease z(settings("z"), t0);
    const auto late = z.tick(t0 + 2s);
    ASSERT_TRUE(late.has_value());
    a.on_record(*late, t0 + 2600ms);
    EXPECT_EQ(a.role(t0 + 2600ms), Role::leader);
    // The broker hands "z" the leader's renewal before its own claim's acknowledgement.
    const auto renewal = a.tick(t0 + 3000ms);
    ASSERT_TRUE(renewal.has_value());
    EXPECT_EQ(*renewal, record("a", 1));
    z.on_record(*renewal, t0 + 3000ms);
    z.on_acknowledged(t0 + 2s);
    z.tick(t0 + 3000ms);
    EXPECT_EQ(z.role(t0 + 3000ms), Role::standby);
    EXPECT_EQ(z.leader_id(), "a");
    EXPECT_EQ(a.role(t0 + 3000ms), Role::leader);
}

TEST(LeaseTest, AStandbyHearingTheLeaderNeverClaims) {
    Lease lease(settings("b"), t0);
    for (auto at = t0; at < t0 + 20s; at += 500ms) {
        lease.on_record(record("a", 3), at);
        EXPECT_FALSE(lease.tick(at + 499ms).has_value());
    }
    EXPECT_EQ(lease.epoch(), 3u);
    EXPECT_EQ(lease.writes(t0 + 20s), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, AClearedRecordDoesNotHastenTheTakeover) {
    Lease lease(settings("b"), t0);
    lease.on_record(record("a", 3), t0 + 1s);
    lease.on_record(std::nullopt, t0 + 1100ms);  // the leader's will
    EXPECT_FALSE(lease.tick(t0 + 2499ms).has_value());
    const auto claim = lease.tick(t0 + 2500ms);
    ASSERT_TRUE(claim.has_value());
    EXPECT_EQ(claim->epoch, 4u);
}

TEST(LeaseTest, ItsOwnRecordFromAnEarlierLifeRaisesTheEpochButIsNotALeader) {
    Lease lease(settings("a"), t0);
    lease.on_record(record("a", 5), t0 + 10ms);
    EXPECT_EQ(lease.writes(t0 + 20ms), WritePolicy::leave_to_leader);
    const auto claim = lease.tick(t0 + 2s);
    ASSERT_TRUE(claim.has_value());
    EXPECT_EQ(claim->epoch, 6u);
}

TEST(LeaseTest, AStartingUnitLeavesWritesToALeaderItMayNotHaveReadYet) {
    Lease lease(settings("b"), t0);
    EXPECT_EQ(lease.writes(t0 + 10ms), WritePolicy::leave_to_leader);
    EXPECT_EQ(lease.writes(t0 + 1499ms), WritePolicy::leave_to_leader);
    // Nobody's record came: it claims (and, leading, settles what it left: PairWrites).
    const auto claim = lease.tick(t0 + 1500ms);
    EXPECT_EQ(lease.writes(t0 + 1500ms), WritePolicy::leave_to_leader);
    claim_taken(lease, claim, t0 + 1500ms);
    lease.tick(t0 + 2000ms);
    EXPECT_EQ(lease.writes(t0 + 2000ms), WritePolicy::apply);
    Lease heard(settings("b"), t0);
    heard.on_record(record("a", 1), t0 + 10ms);
    EXPECT_EQ(heard.writes(t0 + 20ms), WritePolicy::leave_to_leader);
    EXPECT_EQ(heard.writes(t0 + 1260ms), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, AStandbyRefusesNoWriteEvenOnceTheLeaderItHeardIsSurelyFenced) {
    // It may be cut off without knowing; else it settles them once it leads (PairWrites).
    Lease lease(settings("b"), t0);
    lease.on_record(record("a", 1), t0 + 1s);
    EXPECT_EQ(lease.writes(t0 + 2249ms), WritePolicy::leave_to_leader);
    EXPECT_EQ(lease.writes(t0 + 2250ms), WritePolicy::leave_to_leader);
    claim_taken(lease, lease.tick(t0 + 2500ms), t0 + 2500ms);  // its claim
    EXPECT_EQ(lease.writes(t0 + 2600ms), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, ALeaderWhoseLeaseLapsedLeavesWritesToItsSuccessor) {
    auto lease = leader_from(t0 + 2s);
    // The last acknowledged renewal was sent at 2.5 s: fenced at 3.75 s, before any tick.
    EXPECT_EQ(lease.writes(t0 + 3750ms), WritePolicy::leave_to_leader);
    lease.tick(t0 + 3750ms);
    EXPECT_EQ(lease.role(t0 + 3750ms), Role::standby);
    EXPECT_EQ(lease.writes(t0 + 5s), WritePolicy::leave_to_leader);
    // Its successor heard, then late: left still, as by any unit that does not lead.
    lease.on_record(record("b", 2), t0 + 5s);
    EXPECT_EQ(lease.writes(t0 + 6249ms), WritePolicy::leave_to_leader);
    EXPECT_EQ(lease.writes(t0 + 6250ms), WritePolicy::leave_to_leader);
}

TEST(LeaseTest, AcknowledgementsOfAnEarlierLeadershipDoNotCount) {
    auto lease = leader_from(t0 + 2s);
    lease.on_record(record("b", 2), t0 + 2600ms);
    // It claims again later; a late acknowledgement of a renewal sent while it led before
    // must not lift the new claim.
    ASSERT_TRUE(lease.tick(t0 + 4600ms).has_value());
    lease.on_acknowledged(t0 + 2500ms);
    lease.tick(t0 + 5100ms);
    EXPECT_EQ(lease.role(t0 + 5100ms), Role::standby);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
