// The standby of a pair and the writes that reach it (docs/redundancy.md), through the
// WriteDispatcher that asks the pair's PairAdmission: left to a live leader unanswered, refused
// `standby` when no leader answers, always refused on the command port (this unit's own
// address), and taken as ever by the leader; at a takeover, those the old leader never answered
// are settled: taken when the image holds what they write, else refused.

#include "eip2mqtt/app/redundancy/pair_admission.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using core::redundancy::WritePolicy;
using core::write::WriteError;
using core::write::WriteRejection;

class PairAdmissionTest : public ::testing::Test {
protected:
    PairAdmissionTest() { dispatcher_.set_role(admission_); }
    WriteRequest write(WriteOrigin via = WriteOrigin::mqtt) {
        WriteRequest request{{"reply/topic", "id", &origin_},
                             "acme/t1/out/set",
                             ExchangeWrite{&plan_, {{0, core::plan::Value{true}}}},
                             {}};
        request.reply.via = via;
        return request;
    }
    /// A write left to the leader as a standby, then settled by this unit as the new leader,
    /// whose image holds what it writes or not.
    void leave_then_settle(bool image_holds) {
        policy_ = WritePolicy::leave_to_leader;
        dispatcher_.on_write(write());
        ASSERT_EQ(left_.size(), 1u);
        policy_ = WritePolicy::apply;
        holds_ = image_holds;
        taken_ = dispatcher_.settle(std::move(left_[0]));
    }
    bool taken_ = false;  ///< what settle() said
    std::uint64_t refused_standby() const {
        return dispatcher_.counters()
            .writes_rejected[static_cast<std::size_t>(WriteError::standby)];
    }

    test::FakeClock clock_;
    test::RecordingNorthbound origin_;
    core::plan::ExchangePlan plan_;
    int staged_ = 0;
    WritePolicy policy_ = WritePolicy::apply;
    std::vector<WriteRequest> left_;
    bool holds_ = false;
    redundancy::PairAdmission admission_{
        {[this] { return policy_; },
         [this](WriteRequest&& request) { left_.push_back(std::move(request)); },
         [this](const ExchangeWrite&) { return holds_; }}};
    /// Where refusals are answered, as in the gateway: the fan-out, which hands each to its
    /// origin.
    northbound::FanOut results_;
    WriteDispatcher dispatcher_{[this](ExchangeWrite&&, const WriteReply&,
                                       core::MonoTime) -> std::optional<WriteRejection> {
                                    ++staged_;
                                    return std::nullopt;
                                },
                                results_, clock_};
};

TEST_F(PairAdmissionTest, TheLeaderStagesAsEver) {
    dispatcher_.on_write(write());
    EXPECT_EQ(staged_, 1);
    EXPECT_TRUE(origin_.results.empty());
}

TEST_F(PairAdmissionTest, AStandbyWithALiveLeaderDropsTheWriteUnansweredAndCountsIt) {
    policy_ = WritePolicy::leave_to_leader;
    dispatcher_.on_write(write());
    dispatcher_.on_write(write(WriteOrigin::sparkplug));
    EXPECT_EQ(staged_, 0);
    EXPECT_TRUE(origin_.results.empty());
    EXPECT_EQ(dispatcher_.counters().writes_left_to_leader, 2u);
    EXPECT_EQ(refused_standby(), 0u);
}

TEST_F(PairAdmissionTest, AStandbyWithoutALiveLeaderRefusesStandby) {
    policy_ = WritePolicy::refuse;
    dispatcher_.on_write(write());
    EXPECT_EQ(staged_, 0);
    ASSERT_EQ(origin_.results.size(), 1u);
    EXPECT_EQ(origin_.results[0].error, "standby");
    EXPECT_EQ(refused_standby(), 1u);
}

TEST_F(PairAdmissionTest, TheCommandPortOfAStandbyRefusesEvenBesideALiveLeader) {
    policy_ = WritePolicy::leave_to_leader;
    dispatcher_.on_write(write(WriteOrigin::commands));
    EXPECT_EQ(staged_, 0);
    ASSERT_EQ(origin_.results.size(), 1u);
    EXPECT_EQ(origin_.results[0].error, "standby");
}

TEST_F(PairAdmissionTest, AStandbyAnswersEvenAnInvalidWriteOnlyWhenNoLeaderDoes) {
    policy_ = WritePolicy::leave_to_leader;
    auto invalid = write();
    invalid.outcome = WriteRejection{WriteError::read_only, "read-only"};
    dispatcher_.on_write(std::move(invalid));
    EXPECT_TRUE(origin_.results.empty());
}

TEST_F(PairAdmissionTest, AWriteLeftToTheLeaderIsHandedOverUnanswered) {
    policy_ = WritePolicy::leave_to_leader;
    dispatcher_.on_write(write());
    ASSERT_EQ(left_.size(), 1u);
    EXPECT_EQ(left_[0].reply.topic, "reply/topic");
    EXPECT_EQ(left_[0].reply.correlation_data, "id");
    EXPECT_TRUE(origin_.results.empty());
}

TEST_F(PairAdmissionTest, ASettledWriteTheImageHoldsIsTakenAsTheLeaderTakesAny) {
    leave_then_settle(true);
    EXPECT_TRUE(taken_);
    EXPECT_EQ(staged_, 1);  // answered `ok` once produced, by the producer
    EXPECT_TRUE(origin_.results.empty());
    EXPECT_EQ(dispatcher_.counters().writes_settled_applied, 1u);
    EXPECT_EQ(dispatcher_.counters().writes_ok, 1u);
}

TEST_F(PairAdmissionTest, ASettledWriteTheImageDoesNotHoldIsRefusedStandbyUnapplied) {
    leave_then_settle(false);
    EXPECT_FALSE(taken_);
    EXPECT_EQ(staged_, 0);
    ASSERT_EQ(origin_.results.size(), 1u);
    EXPECT_EQ(origin_.results[0].error, "standby");
    EXPECT_EQ(refused_standby(), 1u);
    EXPECT_EQ(dispatcher_.counters().writes_settled_standby, 1u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
