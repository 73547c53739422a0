// The edge node's session alone, time passed in: bdSeq from will to will and from the last
// process's, whether it may publish, and when a host's rebirth requests are answered.

#include "eip2mqtt/app/northbound/sparkplug/node_session.hpp"

#include <gtest/gtest.h>

#include "sparkplug_b.pb.h"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

constexpr auto t0 = core::MonoTime{} + std::chrono::hours(24);

class NodeSessionTest : public ::testing::Test {
protected:
    NodeSessionTest() { session_.tick(t0); }
    /// Connected and born, at t0.
    void born() {
        session_.next_will();
        session_.connected();
        ASSERT_TRUE(session_.begin_birth(false));
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

TEST_F(NodeSessionTest, TheFirstWillGoesOnFromTheLastProcesssBdSeq) {
    NodeSession restarted("spBv1.0/g/NDEATH/n", false, 41);
    EXPECT_EQ(restarted.next_will(), 42);
    NodeSession wrapped("spBv1.0/g/NDEATH/n", false, 255);
    EXPECT_EQ(wrapped.next_will(), 0);
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
    EXPECT_FALSE(session_.begin_birth(false));
    NodeSession hosted("spBv1.0/g/NDEATH/n", true);
    hosted.connected();
    EXPECT_FALSE(hosted.may_publish());
    EXPECT_FALSE(hosted.begin_birth(false));
    hosted.set_host_online(true);
    EXPECT_TRUE(hosted.may_publish());
    EXPECT_TRUE(hosted.begin_birth(false));
}

TEST_F(NodeSessionTest, TheFirstRequestAfterTheConnectionsBirthIsAnsweredAtOnce) {
    born();  // at t0, not asked for
    EXPECT_TRUE(session_.request_birth());
    EXPECT_TRUE(session_.may_send_data());
}

TEST_F(NodeSessionTest, RequestsWithinTheHoldOfAnAnsweredOneWaitForItsEndAndStopData) {
    born();
    ASSERT_TRUE(session_.request_birth());
    ASSERT_TRUE(session_.begin_birth(true));
    session_.set_born();
    EXPECT_TRUE(session_.may_send_data());
    EXPECT_FALSE(session_.request_birth());
    EXPECT_FALSE(session_.request_birth());  // one rebirth for both
    EXPECT_FALSE(session_.may_send_data());  // DATA stops at the request
    EXPECT_TRUE(session_.born());
    session_.tick(t0 + rebirth_hold - std::chrono::milliseconds(1));
    EXPECT_FALSE(session_.birth_due());
    session_.tick(t0 + rebirth_hold);
    EXPECT_TRUE(session_.birth_due());
    EXPECT_TRUE(session_.begin_birth(true));
    EXPECT_FALSE(session_.birth_due());  // the one waiting is this one
    EXPECT_FALSE(session_.born());       // until its NBIRTH is published
    session_.set_born();
    EXPECT_TRUE(session_.may_send_data());
    // It was asked for too: the next request within its hold waits.
    EXPECT_FALSE(session_.request_birth());
}

TEST_F(NodeSessionTest, TheHostGoingOfflineEndsTheBirthsAndAWaitingRebirth) {
    NodeSession hosted("spBv1.0/g/NDEATH/n", true);
    hosted.tick(t0);
    hosted.connected();
    hosted.set_host_online(true);
    ASSERT_TRUE(hosted.begin_birth(true));
    hosted.set_born();
    EXPECT_FALSE(hosted.request_birth());
    hosted.set_host_online(false);
    EXPECT_FALSE(hosted.born());
    EXPECT_FALSE(hosted.may_publish());
    hosted.set_host_online(true);
    hosted.tick(t0 + rebirth_hold);
    EXPECT_FALSE(hosted.birth_due());

    ASSERT_TRUE(hosted.begin_birth(true));
    EXPECT_FALSE(hosted.request_birth());
    hosted.connected();
    EXPECT_FALSE(hosted.host_online());
    hosted.set_host_online(true);
    hosted.tick(t0 + rebirth_hold * 3);
    EXPECT_FALSE(hosted.birth_due());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
