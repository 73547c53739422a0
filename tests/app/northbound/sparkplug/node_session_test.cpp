// The edge node's session alone, time passed in: bdSeq from will to will, whether it may
// publish, and when a birth may start after a rebirth in progress and an NDEATH the broker has
// not acknowledged yet.

#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"

#include <gtest/gtest.h>

#include "sparkplug_b.pb.h"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using Acknowledged = NodeSession::Acknowledged;
using BirthStart = NodeSession::BirthStart;

constexpr auto t0 = core::MonoTime{} + std::chrono::hours(24);

class NodeSessionTest : public ::testing::Test {
protected:
    NodeSessionTest() { session_.tick(t0); }
    /// Connected and born, at t0.
    void born() {
        session_.next_will();
        session_.connected();
        ASSERT_EQ(session_.begin_birth(), BirthStart::started);
        session_.set_born();
    }
    NodeSession session_{"spBv1.0/g/NDEATH/n", false};
};

TEST_F(NodeSessionTest, EachConnectionMadeTakesTheNextBdSeqAndAFailedAttemptKeepsIt) {
    EXPECT_EQ(session_.session_bd_seq(), std::nullopt);
    EXPECT_EQ(session_.next_will(), 0);
    EXPECT_EQ(session_.next_will(), 0);  // the first attempt made no connection
    session_.connected();
    EXPECT_EQ(session_.next_will(), 1);
    EXPECT_EQ(session_.session_bd_seq(), 1);
    session_.end_session();
    EXPECT_EQ(session_.session_bd_seq(), std::nullopt);
}

TEST_F(NodeSessionTest, TheNdeathCarriesTheBdSeqAtQos1) {
    session_.next_will();
    session_.connected();
    session_.next_will();
    const auto death = session_.death_message(1700000000000);
    EXPECT_EQ(death.topic, "spBv1.0/g/NDEATH/n");
    EXPECT_EQ(death.qos, 1);
    EXPECT_FALSE(death.retain);
    org::eclipse::tahu::protobuf::Payload proto;
    ASSERT_TRUE(proto.ParseFromString(death.payload));
    ASSERT_EQ(proto.metrics_size(), 1);
    EXPECT_EQ(proto.metrics(0).name(), "bdSeq");
    EXPECT_EQ(proto.metrics(0).long_value(), 1u);
    EXPECT_EQ(proto.timestamp(), 1700000000000u);
}

TEST_F(NodeSessionTest, NoBirthBeforeTheConnectionNorWithAPrimaryHostOffline) {
    EXPECT_EQ(session_.begin_birth(), BirthStart::refused);
    NodeSession hosted("spBv1.0/g/NDEATH/n", true);
    hosted.connected();
    EXPECT_FALSE(hosted.may_publish());
    EXPECT_EQ(hosted.begin_birth(), BirthStart::refused);
    hosted.set_host_online(true);
    EXPECT_TRUE(hosted.may_publish());
    EXPECT_EQ(hosted.begin_birth(), BirthStart::started);
}

TEST_F(NodeSessionTest, ARebirthAskedDuringTheHoldIsPendingUntilItEnds) {
    born();
    EXPECT_FALSE(session_.request_birth());
    EXPECT_FALSE(session_.birth_due());
    session_.tick(t0 + rebirth_hold - std::chrono::milliseconds(1));
    EXPECT_FALSE(session_.birth_due());
    session_.tick(t0 + rebirth_hold);
    EXPECT_TRUE(session_.birth_due());
    EXPECT_EQ(session_.begin_birth(), BirthStart::started);
    EXPECT_FALSE(session_.birth_due());  // the one pending is this one
    EXPECT_FALSE(session_.born());       // until its NBIRTH is published
}

TEST_F(NodeSessionTest, BirthsWaitForTheNdeathsAcknowledgementOrItsDeadline) {
    born();
    session_.tick(t0 + rebirth_hold);
    const auto token = session_.death_said();
    EXPECT_NE(token & sparkplug_own_token, 0u);
    EXPECT_FALSE(session_.born());
    EXPECT_FALSE(session_.request_birth());
    EXPECT_EQ(session_.acknowledged(token & ~sparkplug_own_token), Acknowledged::not_ours);
    EXPECT_EQ(session_.acknowledged(token + 1), Acknowledged::ours);  // not the one waited for
    EXPECT_FALSE(session_.birth_due());
    EXPECT_EQ(session_.acknowledged(token), Acknowledged::birth_due);
    EXPECT_EQ(session_.begin_birth(), BirthStart::started);

    // Never acknowledged: the births go on at the deadline, and say so.
    session_.set_born();
    session_.tick(t0 + rebirth_hold * 2);
    session_.death_said();
    EXPECT_FALSE(session_.request_birth());
    session_.tick(t0 + rebirth_hold * 2 + death_acknowledgement_timeout);
    EXPECT_TRUE(session_.birth_due());
    EXPECT_EQ(session_.begin_birth(), BirthStart::started_unacknowledged);
}

TEST_F(NodeSessionTest, TheHostGoingOfflineOrANewConnectionDropsAPendingRebirth) {
    NodeSession hosted("spBv1.0/g/NDEATH/n", true);
    hosted.tick(t0);
    hosted.connected();
    hosted.set_host_online(true);
    ASSERT_EQ(hosted.begin_birth(), BirthStart::started);
    EXPECT_FALSE(hosted.request_birth());
    hosted.set_host_online(false);
    hosted.set_host_online(true);
    hosted.tick(t0 + rebirth_hold);
    EXPECT_FALSE(hosted.birth_due());

    ASSERT_EQ(hosted.begin_birth(), BirthStart::started);
    EXPECT_FALSE(hosted.request_birth());
    hosted.connected();
    EXPECT_FALSE(hosted.host_online());
    hosted.set_host_online(true);
    hosted.tick(t0 + rebirth_hold * 3);
    EXPECT_FALSE(hosted.birth_due());
}

}  // namespace
}  // namespace eip2mqtt::app::northbound::sparkplug
