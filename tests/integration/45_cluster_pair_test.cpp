// A hot-standby pair on a real broker cluster: its two units on two different ejabberd nodes
// (gw-a on node 0, gw-b on node 1, each with all three in `mqtt.url`). The leader killed
// (SIGKILL): the standby hears its lease run out through the cluster, and takes over.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <memory>
#include <string>

#include "tests/support/broker_cluster.hpp"
#include "tests/support/pair_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

class EjabberdClusterPairTest : public PairTest {
protected:
    void SetUp() override {
        cluster_ = BrokerCluster::start(BrokerCluster::Kind::ejabberd, 3);
        if (!cluster_) GTEST_SKIP() << "ejabberd is not installed, or the tests do not run as root";
        ASSERT_TRUE(cluster_->ready());
        // Every role as a subscriber on node 2, which neither unit uses, hears it.
        recorder_ = std::make_unique<MqttRecorder>(
            cluster_->url(2), std::vector<std::string>{"test/#"}, "", cluster_->login());
        const auto password = dir_.write("password", cluster_->login().password);
        ::chmod(password.c_str(), 0600);
        const auto login =
            ", username: " + cluster_->login().username + ", password_file: " + password;
        start_units([&](const std::string& id, std::uint16_t port) {
            return pair_config(id, cluster_->url_list(id == "gw-a" ? 0 : 1), port, 100, "", "",
                               login);
        });
    }
    void TearDown() override {
        PairTest::TearDown();
        cluster_.reset();
    }

    std::unique_ptr<BrokerCluster> cluster_;
};

TEST_F(EjabberdClusterPairTest, TheStandbyOnAnotherNodeTakesOverFromAKilledLeader) {
    const auto leader = first_leader();
    ASSERT_FALSE(leader.empty()) << "no unit said leader";
    const auto from = recorder_->count();
    gateways_[leader]->signal(SIGKILL);
    EXPECT_TRUE(says(other(leader), "leader", from, 60s))
        << "the unit on the other node did not take over";
    while (capture_.receive(0ms)) {
    }
    EXPECT_TRUE(capture_.receive(10s).has_value()) << "nothing produced after the takeover";
}

}  // namespace
}  // namespace eip2mqtt::test
