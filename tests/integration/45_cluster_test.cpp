// The gateway on a real broker cluster: three ejabberd nodes on this machine, all three in
// `mqtt.url`, QoS 1, `batch` and store and forward on; the node in use is killed (SIGKILL).
// What a subscriber on a surviving node receives, and what a fresh one finds retained on each
// node, is what docs/brokers.md and docs/scale-out.md say of ejabberd.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "tests/support/ejabberd_cluster.hpp"
#include "tests/support/store_and_forward_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

class EjabberdClusterTest : public StoreAndForwardTest {
protected:
    void SetUp() override {
        if (!EjabberdCluster::available()) GTEST_SKIP() << "ejabberd is not installed";
        cluster_ = std::make_unique<EjabberdCluster>(3);
        ASSERT_TRUE(cluster_->ready());
    }
    void TearDown() override {
        StoreAndForwardTest::TearDown();
        cluster_.reset();
    }

    /// The gateway with the three nodes in `mqtt.url`, the first in use; a watcher on `node`
    /// records everything from before the counter's first datagram on.
    void start_on_cluster(int watched) {
        GatewayOptions options;
        options.wait_online = false;
        std::string urls = "[ \"" + cluster_->url(0) + "\"";
        for (int i = 1; i < cluster_->size(); ++i) urls += ", \"" + cluster_->url(i) + "\"";
        urls += " ]";
        options.url_through = [urls](std::uint16_t) { return urls; };
        options.env["EIP2MQTT_MQTT_PASSWORD"] = EjabberdCluster::login().password;
        start_gateway_with(
            "    enabled: true\n", std::move(options),
            "  username: " + EjabberdCluster::login().username + "\n", [&] {
                ASSERT_TRUE(gateway_->wait_for_output("MQTT connected to " + cluster_->url(0), 90s))
                    << gateway_->output();
                // The fixture's checks read recorder_: the watcher takes its place.
                recorder_ = std::make_unique<MqttRecorder>(cluster_->url(watched),
                                                           std::vector<std::string>{topic("#")}, "",
                                                           EjabberdCluster::login());
            });
    }
    /// Whether a subscriber made now on `node` is given the retained COUNTER at once.
    bool retained_on(int node) {
        MqttRecorder fresh(cluster_->url(node), {topic("line/COUNTER")}, "",
                           EjabberdCluster::login());
        const auto got = fresh.wait_for_message(topic("line/COUNTER"), nullptr, 5s);
        return got.has_value() && got->retained;
    }

    std::unique_ptr<EjabberdCluster> cluster_;
};

TEST_F(EjabberdClusterTest, TheGatewayMovesToASurvivingNodeAndItsSubscribersMissNoSample) {
    start_on_cluster(1);
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 30s))
        << "live values do not cross from node 0 to node 1\n"
        << gateway_->output();

    cluster_->kill(0);
    ASSERT_TRUE(gateway_->wait_for_output("MQTT connected to " + cluster_->url(1), 60s))
        << gateway_->output();
    // The move is over once a value sent after it is live again; then every value sent.
    const auto after_move = counter_->last() + 50;
    ASSERT_TRUE(recorder_->wait_for(
        [&](const auto& all) {
            const auto live = values_on("_values", all);
            return !live.empty() && live.back() >= after_move;
        },
        60s))
        << gateway_->output();
    const auto last = counter_->pause();
    ASSERT_TRUE(wait_all_received(last)) << gateway_->output();
    expect_each_value_once(last);

    // Retained messages are kept per node: the node the gateway moved to has the tree again
    // (its connect republishes it); a node it never used has none of it.
    EXPECT_TRUE(retained_on(1)) << "no retained COUNTER on the node the gateway moved to";
    EXPECT_FALSE(retained_on(2)) << "ejabberd now shares retained messages between nodes: "
                                    "docs/brokers.md and docs/scale-out.md say otherwise";
}

}  // namespace
}  // namespace eip2mqtt::test
