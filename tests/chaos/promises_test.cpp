// The chaos tests' checkers (tests/support/promises.hpp), fed hand-made recordings: a healthy
// one passes, and each one that breaks a promise is caught, with a line that says where.

#include "tests/support/promises.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace eip2mqtt::test::promises {
namespace {

using namespace std::chrono_literals;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::SizeIs;

/// `count` datagrams of `producer` every 50 ms from `from`, request ids from `rid`.
std::vector<Produced> run_of(const std::string& producer, Millis from, int count,
                             std::uint16_t rid = 1, double value = 3000) {
    std::vector<Produced> out;
    for (int i = 0; i < count; ++i) {
        out.push_back({producer, static_cast<std::uint16_t>(rid + i), from + i * 50ms, value});
    }
    return out;
}

std::vector<Produced> joined(std::vector<Produced> a, const std::vector<Produced>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

TEST(OneProducer, ATakeoverAPeriodOrMoreAfterTheLastDatagramHolds) {
    // a's last at 450 ms, b's first at 1,500 ms; then b's last at 1,950 ms, a again at 2,000.
    const auto capture =
        joined(joined(run_of("a", 0ms, 10), run_of("b", 1500ms, 10)), run_of("a", 2000ms, 3, 11));
    EXPECT_THAT(one_producer(capture, 50ms, 10ms), IsEmpty());
}

TEST(OneProducer, TwoUnitsProducingAtOnceAreCaught) {
    const auto capture = joined(run_of("a", 0ms, 10), run_of("b", 225ms, 4, 100));
    const auto found = one_producer(capture, 50ms, 10ms);
    ASSERT_THAT(found, SizeIs(8));  // each of b's four datagrams, on each side
    EXPECT_THAT(found[0], HasSubstr("a (request id 5, at 200 ms) then b (request id 100"));
}

TEST(OneProducer, ANewLeaderLessThanAPeriodAfterTheOldOneIsCaught) {
    const auto capture = joined(run_of("a", 0ms, 3), run_of("b", 130ms, 3));
    EXPECT_THAT(one_producer(capture, 50ms, 10ms), ElementsAre(HasSubstr("30 ms apart")));
    // The capture's own error is allowed for: 45 ms apart is within 10 ms of a period.
    EXPECT_THAT(one_producer(joined(run_of("a", 0ms, 3), run_of("b", 145ms, 3)), 50ms, 10ms),
                IsEmpty());
}

TEST(LeadershipPresent, ATakeoverWithinTakeoverPlusAPeriodHolds) {
    const auto capture = joined(run_of("a", 0ms, 10), run_of("b", 1450ms, 10));
    EXPECT_THAT(leadership_present(capture, {}, 1000ms, 50ms, 100ms, {}, 1950ms), IsEmpty());
}

TEST(LeadershipPresent, ALongerPauseIsCaughtUnlessNoUnitCouldReachTheBroker) {
    // Nobody from 450 ms to 3,000 ms: the stale claims of a unit cut off deposed the leader.
    const auto capture = joined(run_of("a", 0ms, 10), run_of("b", 3000ms, 10));
    EXPECT_THAT(leadership_present(capture, {}, 1000ms, 50ms, 100ms, {}, 3450ms),
                ElementsAre(HasSubstr("from 450 ms to 3000 ms")));
    EXPECT_THAT(leadership_present(capture, {}, 1000ms, 50ms, 100ms, {{1000ms, 2000ms}}, 3450ms),
                IsEmpty());
    // A pause at the end counts too, and a run that produced nothing fails.
    EXPECT_THAT(leadership_present(run_of("a", 0ms, 2), {}, 1000ms, 50ms, 100ms, {}, 5000ms),
                ElementsAre(HasSubstr("until the end of the run")));
    EXPECT_THAT(leadership_present({}, {}, 1000ms, 50ms, 100ms, {}, 5000ms), SizeIs(1));
}

TEST(LeadershipPresent, ALeaderCutOffCountsFromItsLastRenewalHeardBeforeItStoodDown) {
    // a's datagrams stop at 450 ms (cut off), its renewal sent in the cut is heard at 700 ms and
    // it stands down at 720 ms; b leads a takeover later and produces at 1,800 ms.
    const auto capture = joined(run_of("a", 0ms, 10), run_of("b", 1800ms, 10));
    const LeaseHeard cut{{{"a", 1, 200ms}, {"a", 1, 700ms}, {"b", 2, 1750ms}},
                         {{"a", true, 100ms}, {"a", false, 720ms}, {"b", true, 1750ms}}};
    EXPECT_THAT(leadership_present(capture, cut, 1000ms, 50ms, 100ms, {}, 2250ms), IsEmpty());
    // Without the renewal the pause is 1,350 ms; a late production after it is caught all the
    // same, with where it was counted from.
    EXPECT_THAT(leadership_present(capture, {}, 1000ms, 50ms, 100ms, {}, 2250ms),
                ElementsAre(HasSubstr("from 450 ms to 1800 ms")));
    const auto late = joined(run_of("a", 0ms, 10), run_of("b", 2000ms, 10));
    EXPECT_THAT(leadership_present(late, cut, 1000ms, 50ms, 100ms, {}, 2450ms),
                ElementsAre(HasSubstr("from 700 ms to 2000 ms (1300 ms, more than takeover + "
                                      "period + slack = 1150 ms; the last datagram at 450 ms")));
}

TEST(LeadershipPresent, ALeaderThatRenewsAndNeverProducesIsCaught) {
    const LeaseHeard renewing{{{"a", 1, 200ms}, {"a", 1, 700ms}, {"a", 1, 1200ms}},
                              {{"a", true, 100ms}}};
    EXPECT_THAT(leadership_present(run_of("a", 0ms, 10), renewing, 1000ms, 50ms, 100ms, {}, 3000ms),
                ElementsAre(HasSubstr("from 450 ms to 3000 ms")));
}

/// gw-b's renewals every 250 ms from `from` to `to`, epoch `epoch`.
std::vector<Renewal> renewing(const std::string& unit, int epoch, Millis from, Millis to) {
    std::vector<Renewal> out;
    for (auto at = from; at <= to; at += 250ms) out.push_back({unit, epoch, at});
    return out;
}

TEST(LeaderKept, ALeaderFencedByItsOwnCutOrAFailedOneMayStandDown) {
    // gw-b renews until 2,000 ms, is cut off 2,000-4,000 ms, says standby at 4,100 ms.
    auto renewals = renewing("gw-b", 1, 0ms, 2000ms);
    const auto more = renewing("gw-a", 2, 3200ms, 6000ms);
    renewals.insert(renewals.end(), more.begin(), more.end());
    const std::vector<Role> roles{
        {"gw-b", true, 0ms}, {"gw-a", true, 3200ms}, {"gw-b", false, 4100ms}};
    EXPECT_THAT(leader_kept(renewals, roles, {{"gw-b", {2000ms, 4000ms}}}, 500ms, 5000ms),
                IsEmpty());
    // Killed: it never says standby; the new leader's role alone is no step down.
    EXPECT_THAT(
        leader_kept(renewals, {{"gw-b", true, 0ms}, {"gw-a", true, 3200ms}}, {}, 500ms, 5000ms),
        IsEmpty());
}

TEST(LeaderKept, AHealthyLeaderDeposedByAStaleClaimIsCaught) {
    // gw-b renews throughout; gw-a, cut off 2,000-3,000 ms, claims epoch 2 as it comes back,
    // and gw-b stands down at 3,020 ms, its last renewal at 3,000 ms.
    auto renewals = renewing("gw-b", 1, 0ms, 3000ms);
    renewals.push_back({"gw-a", 2, 3300ms});
    const std::vector<Role> roles{
        {"gw-b", true, 0ms}, {"gw-b", false, 3020ms}, {"gw-a", true, 3280ms}};
    EXPECT_THAT(leader_kept(renewals, roles, {{"gw-a", {2000ms, 3000ms}}}, 500ms, 5000ms),
                ElementsAre(HasSubstr("gw-b stood down at 3020 ms while renewing (epoch 1, last "
                                      "renewal at 3000 ms) with no fault of its own: gw-a renews "
                                      "epoch 2 from 3300 ms")));
    // The broker stopped is every unit's fault.
    EXPECT_THAT(leader_kept(renewals, roles, {{"", {2000ms, 3000ms}}}, 500ms, 5000ms), IsEmpty());
}

TEST(LeaderKept, ALeaderWhoseRenewalsStalledWithNoFaultInjectedMayStandDown) {
    // gw-a renews every 250 ms until 1,000 ms; the next two reach the broker together at
    // 1,735 ms, with its standby: its lease was not acknowledged in time.
    auto renewals = renewing("gw-a", 5, 0ms, 1000ms);
    renewals.push_back({"gw-a", 5, 1735ms});
    renewals.push_back({"gw-a", 5, 1735ms});
    const std::vector<Role> roles{{"gw-a", true, 0ms}, {"gw-a", false, 1735ms}};
    EXPECT_THAT(leader_kept(renewals, roles, {}, 500ms, 5000ms), IsEmpty());
    // On time throughout, it stands down for nothing of its own: caught.
    auto steady = renewing("gw-a", 5, 0ms, 1750ms);
    EXPECT_THAT(
        leader_kept(steady, {{"gw-a", true, 0ms}, {"gw-a", false, 1750ms}}, {}, 500ms, 5000ms),
        ElementsAre(HasSubstr("gw-a stood down at 1750 ms while renewing")));
}

std::vector<Sent> sent_upto(std::int64_t last) {
    std::vector<Sent> out;
    for (std::int64_t n = 1; n <= last; ++n) {
        out.push_back({n, "COUNT=" + std::to_string(n), Millis(n * 20)});
    }
    return out;
}

Published on(const std::string& topic, std::int64_t n, Millis at) {
    return {topic, n, "COUNT=" + std::to_string(n), at};
}

TEST(PublishedWasSent, OnlyValuesThePlcSentPass) {
    auto sent = sent_upto(3);
    sent.push_back({2, "COUNT=2,NOISE=7", 45ms});  // a corrupted copy is on the wire too
    EXPECT_THAT(published_was_sent(sent, {on("v", 1, 30ms), {"v", 2, "COUNT=2,NOISE=7", 60ms}}),
                IsEmpty());
    EXPECT_THAT(published_was_sent(sent, {{"v", 2, "COUNT=2,NOISE=8", 60ms}}),
                ElementsAre(HasSubstr("COUNT=2,NOISE=8, which the PLC never sent")));
    EXPECT_THAT(published_was_sent(sent, {on("v", 900, 60ms)}), SizeIs(1));
}

TEST(SamplesOnceInOrder, ATakeoverWithItsHistoryHolds) {
    // 1-5 live from the old leader, 4-7 replayed by the new one, 8-10 live: 4 and 5 on both
    // topics, as docs/redundancy.md allows, each topic once and in order.
    std::vector<Published> published;
    for (std::int64_t n = 1; n <= 5; ++n) published.push_back(on("v", n, Millis(n * 20 + 5)));
    for (std::int64_t n = 4; n <= 7; ++n) published.push_back(on("h", n, 1200ms));
    for (std::int64_t n = 8; n <= 10; ++n) published.push_back(on("v", n, 1300ms));
    EXPECT_THAT(
        samples_once_in_order(sent_upto(10), {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, published, {}, 0ms),
        IsEmpty());
}

TEST(SamplesOnceInOrder, ALostSampleATwiceAndAStepBackAreCaught) {
    const std::vector<Published> published{on("v", 1, 25ms), on("v", 3, 65ms), on("h", 5, 900ms),
                                           on("h", 4, 950ms), on("h", 5, 990ms)};
    const auto found = samples_once_in_order(sent_upto(5), {1, 2, 3}, published, {}, 0ms);
    EXPECT_THAT(found, ElementsAre(HasSubstr("sample 4 back in time, after 5"),
                                   HasSubstr("h at 990 ms: sample 5 twice"),
                                   HasSubstr("sample 2, delivered to both units, never")));
}

TEST(SamplesOnceInOrder, AQos1RepeatAfterAPathCameBackIsExcusedButNotOneSentDuringTheCut) {
    // Samples 1-3 live; the path down from 70 to 500 ms; 2 and 3 again after it (in flight at
    // the cut), then 4-6 sent during the cut and published, then 5 again (a fenced unit's
    // replay after the heal).
    const std::vector<Published> published{on("v", 1, 25ms),  on("v", 2, 45ms),  on("v", 3, 65ms),
                                           on("v", 2, 520ms), on("v", 3, 521ms), on("h", 4, 400ms),
                                           on("h", 5, 401ms), on("h", 6, 402ms), on("h", 5, 600ms)};
    const auto found = samples_once_in_order(sent_upto(6), {}, published, {{70ms, 500ms}}, 0ms);
    EXPECT_THAT(found, ElementsAre(HasSubstr("h at 600 ms: sample 5 twice and back in time")));
}

TEST(SamplesOnceInOrder, WhatALeaderHandedToItsConnectionBeforeItsLeaseLapsedMayComeLate) {
    // Cut at 70 ms; the leader goes on taking samples 4 and 5 (sent at 80 and 100 ms) until its
    // lease lapses, 40 ms later at the latest here; they reach the broker after the heal at
    // 500 ms, behind the new leader's 6. Sample 6 again after the heal is not excused: it was
    // sent at 120 ms, after the lapse.
    const std::vector<Published> published{on("v", 1, 25ms),  on("v", 2, 45ms),  on("v", 3, 65ms),
                                           on("v", 6, 400ms), on("v", 4, 510ms), on("v", 5, 511ms),
                                           on("v", 6, 512ms)};
    const auto found = samples_once_in_order(sent_upto(6), {}, published, {{70ms, 500ms}}, 40ms);
    EXPECT_THAT(found, ElementsAre(HasSubstr("v at 512 ms: sample 6 twice")));
    // Without the lapse, the late 4 and 5 are caught as well.
    EXPECT_THAT(samples_once_in_order(sent_upto(6), {}, published, {{70ms, 500ms}}, 0ms),
                SizeIs(3));
}

TEST(WritesAnsweredOnce, OneAnswerPerWriteAndOkOnTheWireHolds) {
    const std::vector<Write> writes{{"w1", 1001, 100ms}, {"w2", 1002, 200ms}};
    const std::vector<Answer> answers{{"w1", true, "", 180ms}, {"w2", false, "standby", 260ms}};
    const auto capture = joined(run_of("a", 0ms, 3), run_of("a", 150ms, 3, 4, 1001));
    EXPECT_THAT(writes_answered_once(writes, answers, capture, 100ms), IsEmpty());
}

TEST(WritesAnsweredOnce, TwoWritesAppliedToOneProductionAreBothCarried) {
    // Delivered together after a cut: the datagram carries the later value; both are ok.
    const std::vector<Write> writes{{"w1", 1001, 100ms}, {"w2", 1002, 120ms}};
    const std::vector<Answer> answers{{"w1", true, "", 700ms}, {"w2", true, "", 700ms}};
    const auto capture = run_of("a", 650ms, 2, 1, 1002);
    EXPECT_THAT(writes_answered_once(writes, answers, capture, 100ms), IsEmpty());
    // A datagram long after the answer proves nothing: 1002 first left at 2,000 ms.
    EXPECT_THAT(writes_answered_once(writes, answers, run_of("a", 2000ms, 2, 1, 1002), 100ms),
                SizeIs(2));
}

TEST(WritesAnsweredOnce, TwiceContradictedUnansweredAndOkNeverProducedAreCaught) {
    const std::vector<Write> writes{
        {"w1", 1001, 100ms}, {"w2", 1002, 200ms}, {"w3", 1003, 300ms}, {"w4", 1004, 400ms}};
    const std::vector<Answer> answers{{"w1", true, "", 180ms},
                                      {"w1", false, "standby", 1800ms},
                                      {"w2", false, "standby", 260ms},
                                      {"w2", false, "standby", 2260ms},
                                      {"w4", true, "", 480ms}};
    // 1001 went on the wire; 1004 only before its write was sent (another unit's old image).
    const auto capture = joined(run_of("a", 150ms, 2, 1, 1001), run_of("a", 0ms, 1, 9, 1004));
    EXPECT_THAT(writes_answered_once(writes, answers, capture, 100ms),
                ElementsAre(HasSubstr("write w1 (1001.000000, at 100 ms) contradicted: ok at 180 "
                                      "ms, standby at 1800 ms"),
                            HasSubstr("write w2 (1002.000000, at 200 ms) answered 2 times"),
                            HasSubstr("write w3 (1003.000000, at 300 ms) never answered"),
                            HasSubstr("w4 (1004.000000, at 400 ms) answered ok, but no datagram")));
}

TEST(WritesAnsweredOnce, AWriteLostWithAKilledBrokerIsExcusedFromAnAnswerNotFromTwo) {
    // Mosquitto killed from 1,000 to 2,500 ms; an answer is due within 500 ms of a write.
    const std::vector<Write> writes{{"w1", 1001, 300ms},
                                    {"w2", 1002, 600ms},
                                    {"w3", 1003, 2000ms},
                                    {"w4", 1004, 2700ms},
                                    {"w5", 1005, 900ms}};
    const std::vector<Answer> answers{{"w5", false, "standby", 950ms},
                                      {"w5", false, "standby", 3000ms}};
    const std::vector<Span> killed{{1000ms, 2500ms}};
    EXPECT_THAT(writes_answered_once(writes, answers, {}, 100ms, killed, 500ms),
                ElementsAre(HasSubstr("write w1 (1001.000000, at 300 ms) never answered"),
                            HasSubstr("write w4 (1004.000000, at 2700 ms) never answered"),
                            HasSubstr("write w5 (1005.000000, at 900 ms) answered 2 times")));
}

TEST(WritesAnsweredOnce, TheKillsExcuseReachesAsFarBackAsTheRunsOwnPaceAdds) {
    // Mosquitto killed from 10,000 to 12,000 ms; the horizon is 2,100 ms. Away from the kill,
    // w1 took 300 ms to be answered: the machine's pace this run.
    const std::vector<Write> writes{
        {"w1", 1001, 1000ms}, {"w2", 1002, 7700ms}, {"w3", 1003, 7500ms}};
    const std::vector<Answer> answers{{"w1", false, "standby", 1300ms}};
    const std::vector<Span> killed{{10000ms, 12000ms}};
    // w2, 2,300 ms before the kill, is within 2,100 + 300; w3, 2,500 ms before, is not.
    EXPECT_THAT(writes_answered_once(writes, answers, {}, 100ms, killed, 2100ms),
                ElementsAre(HasSubstr("write w3 (1003.000000, at 7500 ms) never answered")));
}

TEST(WritesAnsweredOnce, TheSameAnswerAgainAcrossACutIsQosOnesRepeatNothingElseIs) {
    // The path to the broker cut from 1,000 to 1,500 ms; an answer is due within 500 ms.
    // w5: the new leader answers again what the cut leader's image listed, after the cut; the
    // cut leader's own answer comes later still, its connection back (chaos seed 15).
    const std::vector<Write> writes{{"w1", 1001, 800ms},
                                    {"w2", 1002, 100ms},
                                    {"w3", 1003, 850ms},
                                    {"w4", 1004, 1600ms},
                                    {"w5", 1005, 950ms}};
    const std::vector<Answer> answers{
        {"w1", false, "standby", 900ms},  {"w1", false, "standby", 1600ms},    // in flight: excused
        {"w2", false, "standby", 200ms},  {"w2", false, "standby", 1700ms},    // long before it
        {"w3", false, "standby", 950ms},  {"w3", false, "above max", 1650ms},  // disagrees
        {"w4", false, "standby", 1700ms}, {"w4", false, "standby", 1800ms},    // after it
        {"w5", false, "standby", 1550ms}, {"w5", false, "standby", 1900ms}};   // excused
    const std::vector<Span> cut{{1000ms, 1500ms}};
    EXPECT_THAT(writes_answered_once(writes, answers, {}, 100ms, {}, 500ms, cut),
                ElementsAre(HasSubstr("write w2 (1002.000000, at 100 ms) answered 2 times"),
                            HasSubstr("write w3 (1003.000000, at 850 ms) contradicted"),
                            HasSubstr("write w4 (1004.000000, at 1600 ms) answered 2 times")));
}

TEST(Report, NamesTheCheckerOnEachLine) {
    EXPECT_EQ(report("one producer", {"x", "y"}), "one producer: x\none producer: y\n");
    EXPECT_EQ(report("one producer", {}), "");
}

}  // namespace
}  // namespace eip2mqtt::test::promises
