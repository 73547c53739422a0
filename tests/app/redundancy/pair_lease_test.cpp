// The lease of a pair at run time, against a recording publisher: what it subscribes to, what
// it publishes and when, and how what it reads turns its role. The lease's own rules are
// tested in tests/core/redundancy/lease_test.cpp.

#include "eip2mqtt/app/redundancy/pair_lease.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "eip2mqtt/app/redundancy/leader_record.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::redundancy::LeaderRecord;
using core::redundancy::Role;

const core::MonoTime t0{std::chrono::hours(1)};
const std::string leader_topic = "acme/_gateway/_pair/turbine/leader";
const std::string role_topic = "acme/_gateway/gw-a/role";

class PairLeaseTest : public ::testing::Test {
protected:
    adapters::mqtt::Incoming record(const std::string& id, std::uint64_t epoch) {
        return {leader_topic, encode_leader_record({id, epoch, 0}, 2000ms)};
    }
    /// The last publication on the leader topic, acknowledged as the broker would, and heard
    /// back (the pair's connection hears its own records).
    void acknowledge_last() {
        for (auto it = publisher_.published.rbegin(); it != publisher_.published.rend(); ++it) {
            if (it->topic != leader_topic) continue;
            lease_.on_acknowledged(it->ack_token);
            return lease_.on_message({it->topic, it->payload}, t0);
        }
        FAIL() << "nothing published on the leader topic";
    }

    test::RecordingPublisher publisher_;
    std::vector<Role> roles_;
    PairLease lease_{{"gw-a", 0, 2000ms, 100ms},
                     pair_topics("acme", "turbine", "gw-a"),
                     publisher_,
                     t0,
                     [this](Role role) { roles_.push_back(role); }};
};

TEST_F(PairLeaseTest, TopicsAndWill) {
    const auto topics = pair_topics("acme", "turbine", "gw-a");
    EXPECT_EQ(topics.leader, leader_topic);
    EXPECT_EQ(topics.role, role_topic);
    EXPECT_EQ(topics.images, "acme/_gateway/_pair/turbine/image");
    const auto will = pair_will(topics);
    EXPECT_EQ(will.topic, leader_topic);
    EXPECT_TRUE(will.payload.empty());
    EXPECT_TRUE(will.retain);
    EXPECT_EQ(will.qos, 1);
}

TEST_F(PairLeaseTest, ItSubscribesToTheLeaderTopicAndSaysStandbyOnConnect) {
    EXPECT_EQ(publisher_.subscriptions,
              (std::vector<std::string>{leader_topic, "acme/_gateway/_pair/turbine/image/#"}));
    lease_.on_connected();
    EXPECT_EQ(publisher_.on(role_topic), std::vector<std::string>{"standby"});
    EXPECT_TRUE(publisher_.published.back().retain);
}

TEST_F(PairLeaseTest, AClaimAcknowledgedLeadsThenRenewsEveryQuarter) {
    lease_.tick(t0 + 1499ms);
    EXPECT_TRUE(publisher_.on(leader_topic).empty());
    lease_.tick(t0 + 1500ms);
    ASSERT_EQ(publisher_.on(leader_topic).size(), 1u);
    const auto& claim = publisher_.published.back();
    EXPECT_TRUE(claim.retain);
    EXPECT_EQ(claim.qos, 1);
    EXPECT_NE(claim.ack_token, 0u);
    EXPECT_EQ(decode_leader_record(claim.payload), (LeaderRecord{"gw-a", 1, 0, true}));
    acknowledge_last();
    lease_.tick(t0 + 2s);
    EXPECT_TRUE(lease_.leading(t0 + 2s));
    EXPECT_EQ(roles_, std::vector<Role>{Role::leader});
    EXPECT_EQ(publisher_.on(role_topic), std::vector<std::string>{"leader"});
    EXPECT_EQ(publisher_.on(leader_topic).size(), 2u);  // the claim, then its first renewal
}

TEST_F(PairLeaseTest, ANewerEpochFromThePeerStepsTheLeaderDown) {
    lease_.tick(t0 + 2s);
    acknowledge_last();
    lease_.tick(t0 + 2500ms);
    lease_.on_message(record("gw-b", 2), t0 + 2600ms);
    EXPECT_FALSE(lease_.leading(t0 + 2600ms));
    EXPECT_EQ(roles_, (std::vector<Role>{Role::leader, Role::standby}));
    EXPECT_EQ(publisher_.on(role_topic), (std::vector<std::string>{"leader", "standby"}));
}

TEST_F(PairLeaseTest, WithoutAcknowledgementsTheLeaderIsFencedByTimeAlone) {
    lease_.tick(t0 + 2s);
    acknowledge_last();
    lease_.tick(t0 + 2500ms);
    acknowledge_last();
    EXPECT_TRUE(lease_.may_produce(t0 + 2500ms));
    EXPECT_FALSE(lease_.may_produce(t0 + 2500ms + 1250ms));
    lease_.tick(t0 + 2500ms + 1250ms);
    EXPECT_EQ(roles_, (std::vector<Role>{Role::leader, Role::standby}));
}

TEST_F(PairLeaseTest, OtherTopicsAndPayloadsThatAreNoRecordChangeNothing) {
    lease_.on_message({"acme/other", encode_leader_record({"gw-b", 9, 0}, 2000ms)}, t0 + 1s);
    lease_.on_message({leader_topic, "not json"}, t0 + 1s);
    EXPECT_EQ(lease_.lease().epoch(), 0u);
    lease_.on_message(record("gw-b", 4), t0 + 1s);
    EXPECT_EQ(lease_.lease().epoch(), 4u);
}

TEST_F(PairLeaseTest, RenewalsCarryTheBdSeqOfTheOpenSparkplugSessionClaimsNone) {
    std::optional<std::uint8_t> session;
    lease_.set_bd_seq_source([&session] { return session; });
    session = 9;  // whatever the source says, a claim has no session yet
    lease_.tick(t0 + 2s);
    EXPECT_FALSE(decode_leader_record(publisher_.on(leader_topic).back())->bd_seq.has_value());
    acknowledge_last();
    session.reset();
    lease_.tick(t0 + 2500ms);  // confirmed, its session not open yet
    EXPECT_FALSE(decode_leader_record(publisher_.on(leader_topic).back())->bd_seq.has_value());
    session = 9;
    lease_.tick(t0 + 3000ms);
    EXPECT_EQ(decode_leader_record(publisher_.on(leader_topic).back())->bd_seq, 9);
}

TEST_F(PairLeaseTest, TheBdSeqHeardIsTheNewestOfTheLeasesEpoch) {
    const auto with_bd_seq = [](const std::string& id, std::uint64_t epoch, std::uint8_t bd_seq) {
        LeaderRecord record{id, epoch, 0};
        record.bd_seq = bd_seq;
        return adapters::mqtt::Incoming{leader_topic, encode_leader_record(record, 2000ms)};
    };
    EXPECT_FALSE(lease_.heard_bd_seq().has_value());
    lease_.on_message(record("gw-b", 3), t0 + 100ms);
    EXPECT_FALSE(lease_.heard_bd_seq().has_value());
    lease_.on_message(with_bd_seq("gw-b", 3, 40), t0 + 200ms);
    EXPECT_EQ(lease_.heard_bd_seq(), 40);
    lease_.on_message(record("gw-b", 3), t0 + 300ms);  // a renewal made before its session
    EXPECT_EQ(lease_.heard_bd_seq(), 40);
    lease_.on_message(with_bd_seq("gw-b", 4, 41), t0 + 400ms);
    EXPECT_EQ(lease_.heard_bd_seq(), 41);
    // A renewal of a deposed leader, delivered late: its session is over.
    lease_.on_message(with_bd_seq("gw-c", 3, 17), t0 + 500ms);
    EXPECT_EQ(lease_.heard_bd_seq(), 41);
}

TEST_F(PairLeaseTest, RenewalsCarryTheWatermarksAndTheStandbyHearsTheLeaders) {
    const Watermarks mine{{"line", {7, 1700000000, 5}}};
    std::vector<Watermarks> heard;
    lease_.set_watermarks([&] { return mine; },
                          [&](Watermarks&& watermarks) { heard.push_back(std::move(watermarks)); });
    lease_.tick(t0 + 2s);  // a claim: nothing acknowledged yet
    Watermarks read;
    decode_leader_record(publisher_.on(leader_topic).back(), &read);
    EXPECT_TRUE(read.empty());
    acknowledge_last();
    lease_.tick(t0 + 2500ms);  // the first renewal
    decode_leader_record(publisher_.on(leader_topic).back(), &read);
    EXPECT_EQ(read, mine);

    const Watermarks theirs{{"line", {9, 0, 0}}};
    lease_.on_message({leader_topic, encode_leader_record({"gw-b", 2, 0, true}, 2000ms, theirs)},
                      t0 + 2600ms);
    EXPECT_TRUE(heard.empty()) << "a claim's";
    lease_.on_message({leader_topic, encode_leader_record({"gw-b", 2, 0}, 2000ms, theirs)},
                      t0 + 2700ms);
    EXPECT_EQ(heard, std::vector<Watermarks>{theirs});
    // A deposed leader's, late, and this unit's own from before a restart: not the leader's.
    lease_.on_message({leader_topic, encode_leader_record({"gw-c", 1, 0}, 2000ms, theirs)},
                      t0 + 2800ms);
    lease_.on_message({leader_topic, encode_leader_record({"gw-a", 1, 0}, 2000ms, theirs)},
                      t0 + 2800ms);
    EXPECT_EQ(heard.size(), 1u);
}

TEST_F(PairLeaseTest, NoClaimWhileThePairConnectionIsDown) {
    lease_.on_connection(false, t0);
    lease_.tick(t0 + 1500ms);
    lease_.tick(t0 + 5s);
    EXPECT_TRUE(publisher_.on(leader_topic).empty());
    lease_.on_connection(true, t0 + 5s);
    lease_.tick(t0 + 6499ms);
    EXPECT_TRUE(publisher_.on(leader_topic).empty());
    lease_.tick(t0 + 6500ms);
    ASSERT_EQ(publisher_.on(leader_topic).size(), 1u);
    const auto claim = decode_leader_record(publisher_.published.back().payload);
    ASSERT_TRUE(claim.has_value());
    EXPECT_TRUE(claim->claim);
    // Its beat is its sending time, as its acknowledgement token.
    EXPECT_EQ(claim->beat, publisher_.published.back().ack_token);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
