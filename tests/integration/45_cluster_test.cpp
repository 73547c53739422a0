// The gateway on a real broker cluster: three nodes of ejabberd (MQTT 5) or of RabbitMQ (MQTT
// 3.1.1) on this machine, all three in `mqtt.url`, QoS 1; the node in use is killed (SIGKILL).
// With `batch` and store and forward, a counter; with a produced exchange, a write sent through
// the node the gateway never used; with Sparkplug, the edge node's next session.
// What a subscriber on a surviving node receives (the will of the killed node's session
// included), and what a fresh one finds retained on each node, is what docs/brokers.md and
// docs/scale-out.md say of each broker.

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/broker_cluster.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/store_and_forward_fixture.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

using Kind = BrokerCluster::Kind;

/// A gateway's options on `cluster`: every node in `mqtt.url`, the first first, and the
/// password of its login() (the rest goes in the mqtt section: BrokerCluster::mqtt_keys()).
GatewayOptions on_cluster(const BrokerCluster& cluster) {
    GatewayOptions options;
    options.wait_online = false;
    options.url_through = [urls = cluster.url_list()](std::uint16_t) { return urls; };
    options.env["EIP2MQTT_MQTT_PASSWORD"] = cluster.login().password;
    return options;
}

/// Starts a three-node cluster of `kind` for the test, or says why it cannot.
std::unique_ptr<BrokerCluster> start_cluster(Kind kind, std::string& why_not) {
    auto cluster = BrokerCluster::start(kind, 3);
    if (!cluster) {
        why_not = BrokerCluster::name(kind) + " is not installed, or the tests do not run as root";
    }
    return cluster;
}

std::string kind_name(const testing::TestParamInfo<Kind>& info) {
    return BrokerCluster::name(info.param);
}

class ClusterTest : public StoreAndForwardTest, public testing::WithParamInterface<Kind> {
protected:
    void SetUp() override {
        std::string why_not;
        cluster_ = start_cluster(GetParam(), why_not);
        if (!cluster_) GTEST_SKIP() << why_not;
        ASSERT_TRUE(cluster_->ready());
    }
    void TearDown() override {
        StoreAndForwardTest::TearDown();
        cluster_.reset();
    }

    /// The gateway on the cluster, node 0 in use; a watcher on `watched` records everything
    /// from before the counter's first datagram on.
    void start_on_cluster(int watched) {
        start_gateway_with(
            "    enabled: true\n", on_cluster(*cluster_), cluster_->mqtt_keys(), [&] {
                ASSERT_TRUE(gateway_->wait_for_output("MQTT connected to " + cluster_->url(0), 90s))
                    << gateway_->output();
                // The fixture's checks read recorder_: the watcher takes its place.
                recorder_ = std::make_unique<MqttRecorder>(cluster_->url(watched),
                                                           std::vector<std::string>{topic("#")}, "",
                                                           cluster_->login());
            });
    }
    /// Whether a subscriber made now on `node` is given the retained COUNTER at once.
    bool retained_on(int node) {
        MqttRecorder fresh(cluster_->url(node), {topic("line/COUNTER")}, "", cluster_->login());
        const auto got = fresh.wait_for_message(topic("line/COUNTER"), nullptr, 5s);
        return got.has_value() && got->retained;
    }

    std::unique_ptr<BrokerCluster> cluster_;
};

TEST_P(ClusterTest, TheGatewayMovesToASurvivingNodeAndItsSubscribersMissNoSample) {
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
    // How long the move held samples back shows here: what waited went on `_history`.
    std::cout << "the move: " << values_on("_history").size() << " of " << last
              << " values replayed on _history, the rest live\n";

    // The will of the connection to node 0 died with node 0: nobody was told `offline`; the
    // connect to node 1 said `online`.
    const auto states = recorder_->messages_on(availability_topic());
    EXPECT_TRUE(std::none_of(states.begin(), states.end(),
                             [](const Received& m) { return m.payload == "offline"; }))
        << BrokerCluster::name(GetParam())
        << " now publishes the will of a session whose node died: the docs say otherwise";
    EXPECT_TRUE(std::any_of(states.begin(), states.end(),
                            [](const Received& m) { return m.payload == "online"; }));

    // Retained messages are kept per node: the node the gateway moved to has the tree again
    // (its connect republishes it); a node it never used has none of it.
    EXPECT_TRUE(retained_on(1)) << "no retained COUNTER on the node the gateway moved to";
    EXPECT_FALSE(retained_on(2)) << BrokerCluster::name(GetParam())
                                 << " now shares retained messages between nodes: "
                                    "docs/brokers.md and docs/scale-out.md say otherwise";
}

INSTANTIATE_TEST_SUITE_P(Brokers, ClusterTest, testing::Values(Kind::ejabberd, Kind::rabbitmq),
                         kind_name);

/// The gateway on the cluster with one produced exchange (`sp`, a writable SPEED_SP), a device
/// that always has values.
class ClusterProducingTest : public GatewayTest, public testing::WithParamInterface<Kind> {
protected:
    void SetUp() override {
        std::string why_not;
        cluster_ = start_cluster(GetParam(), why_not);
        if (!cluster_) GTEST_SKIP() << why_not;
        ASSERT_TRUE(cluster_->ready());
        capture_ = std::make_unique<UdpClient>();
    }
    void TearDown() override {
        GatewayTest::TearDown();
        cluster_.reset();
    }
    /// Starts the gateway with `sections` and waits until its connection `log_name` is on node 0.
    void start_producing(const std::string& sections, const std::string& log_name) {
        auto options = on_cluster(*cluster_);
        options.sections = sections;
        start(
            ExchangeYaml::produce("sp", "10.1.2.3", 10,
                                  "127.0.0.1:" + std::to_string(capture_->port()))
                .period_ms(20)
                .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
                .str(),
            cluster_->mqtt_keys(), std::move(options));
        ASSERT_TRUE(gateway_->wait_for_output(log_name + " connected to " + cluster_->url(0), 90s))
            << gateway_->output();
    }
    /// SPEED_SP in the next datagram the gateway sends.
    Value next_speed() {
        while (capture_->receive(0ms)) {
        }
        const auto bytes = capture_->receive(5s);
        if (!bytes) return Value{false};
        return core::plan::decode_value(std::span(*bytes).subspan(32), TagType::real,
                                        core::plan::parse_address("0.0").value());
    }

    std::unique_ptr<BrokerCluster> cluster_;
    std::unique_ptr<UdpClient> capture_;
};

// A write sent through a node the gateway never used, after the gateway's node was killed.
TEST_P(ClusterProducingTest, AWriteThroughASurvivingNodeIsAppliedAndAnsweredOnce) {
    ASSERT_NO_FATAL_FAILURE(start_producing("", "MQTT"));
    const auto result_topic = topic("sp/SPEED_SP/set/result");
    MqttRecorder writer(cluster_->url(2), {result_topic, availability_topic()}, "",
                        cluster_->login());
    cluster_->kill(0);
    // `online` from the node the gateway moved to: its write topics are subscribed there (the
    // node takes one connection's packets in order, the SUBSCRIBE before it).
    ASSERT_TRUE(writer.wait_for_message(
        availability_topic(), [](const std::string& p) { return p == "online"; }, 60s))
        << gateway_->output();
    ASSERT_NE(gateway_->output().find("MQTT connected to " + cluster_->url(1)), std::string::npos)
        << gateway_->output();

    auto from = writer.count();
    writer.publish(topic("sp/SPEED_SP/set"), "1234.5");
    const auto answer = writer.wait_for_message(result_topic, nullptr, 10s, from);
    ASSERT_TRUE(answer.has_value()) << gateway_->output();
    EXPECT_EQ(json::parse(answer->payload), json({{"ok", true}}));
    EXPECT_EQ(next_speed(), Value{1234.5F});
    // A second write, answered after the first: one answer each, none repeated before it.
    from = writer.count();
    writer.publish(topic("sp/SPEED_SP/set"), "2345.5");
    ASSERT_TRUE(writer.wait_for_message(result_topic, nullptr, 10s, from).has_value());
    EXPECT_EQ(writer.messages_on(result_topic).size(), 2u);
    EXPECT_EQ(next_speed(), Value{2345.5F});
}

// The Sparkplug edge node (its own connection, the same list of nodes) after its node was killed.
TEST_P(ClusterProducingTest, TheEdgeNodeStartsItsNextSessionWhereTheBrokerLetsItSubscribe) {
    ASSERT_NO_FATAL_FAILURE(
        start_producing("sparkplug:\n  group_id: plant1\n", "MQTT (Sparkplug)"));
    const std::string node = "spBv1.0/plant1/NBIRTH/test-gw";
    MqttRecorder host(cluster_->url(2), {"spBv1.0/plant1/#"}, "", cluster_->login());
    cluster_->kill(0);
    if (GetParam() == Kind::rabbitmq) {
        // The queue of its QoS 1 subscriptions is on the killed node: the next node closes its
        // connection as it subscribes again (the JSON tree's connection, at QoS 0, moved).
        EXPECT_TRUE(gateway_->wait_for_output("MQTT connected to " + cluster_->url(1), 60s));
        EXPECT_TRUE(gateway_->wait_for_output(
            "MQTT (Sparkplug) subscribe failed on " + cluster_->url(1), 60s))
            << "RabbitMQ now lets a QoS 1 subscriber move: docs/brokers.md says otherwise\n"
            << gateway_->output();
        return;
    }
    ASSERT_TRUE(gateway_->wait_for_output("MQTT (Sparkplug) connected to " + cluster_->url(1), 60s))
        << gateway_->output();
    const auto nbirth = host.wait_for_message(node, nullptr, 30s);
    ASSERT_TRUE(nbirth.has_value()) << "no NBIRTH from the node the gateway moved to";
    const auto birth = tahu_decode(nbirth->payload);
    EXPECT_EQ(birth["seq"], "0");
    EXPECT_EQ(tahu_metric(birth, "bdSeq")["value"], "1") << "a new session, the next bdSeq";
    const auto dbirth = host.wait_for_message("spBv1.0/plant1/DBIRTH/test-gw/sp", nullptr, 30s);
    ASSERT_TRUE(dbirth.has_value());
    EXPECT_EQ(tahu_metric(tahu_decode(dbirth->payload), "SPEED_SP")["value"], 3000);
    // The first session's NDEATH was its will on the killed node: it died with it.
    EXPECT_TRUE(host.messages_on("spBv1.0/plant1/NDEATH/test-gw").empty())
        << BrokerCluster::name(GetParam())
        << " now publishes the will of a session whose node died: the docs say otherwise";
}

INSTANTIATE_TEST_SUITE_P(Brokers, ClusterProducingTest,
                         testing::Values(Kind::ejabberd, Kind::rabbitmq), kind_name);

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
