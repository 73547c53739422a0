// The Sparkplug edge node as a module, against a real Mosquitto: with a single unit's role its
// connection starts at start() and the node is born; with a role whose sessions follow it (a
// fake role) nothing connects until open_session(), and end_session() says the node's NDEATH.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "sparkplug_b.pb.h"
#include "tests/app/support/northbound_rig.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

/// A role whose sessions open when it is taken; it fences nothing, and is never taken here
/// but by the test's open_session().
class FollowingRole final : public redundancy::Role {
public:
    MaySend may_send(MaySend) override { return nullptr; }
    ExchangesOptions exchanges_options() override { return {}; }
    std::unique_ptr<adapters::mqtt::Publisher> session_gate(adapters::mqtt::Publisher&) override {
        return nullptr;
    }
    bool sessions_follow_role() const override { return true; }
    void wire(redundancy::RoleParts) override {}
};

std::string sparkplug_section(const std::string& edge_node_id) {
    return "sparkplug:\n  group_id: plant1\n  edge_node_id: " + edge_node_id + "\n";
}

class SparkplugModuleTest : public test::NorthboundRig {
protected:
    SparkplugModuleTest() : recorder_(broker_.url(), {"spBv1.0/plant1/#"}) {}

    std::unique_ptr<SparkplugModule> make(const std::string& edge_node_id,
                                          const NorthboundParts& parts) {
        auto module = make_sparkplug(config(broker_.url(), "", sparkplug_section(edge_node_id)),
                                     parts, nullptr);
        EXPECT_NE(module, nullptr);
        return module;
    }
    void make_parts_of(std::unique_ptr<redundancy::Role> role) {
        config_ = config(broker_.url(), "", sparkplug_section("n1"));
        make_parts(std::move(role));
    }
    /// Runs the loop, ticking `module`, until the recorder holds a message on `topic`.
    bool seen(SparkplugModule& module, const std::string& topic) {
        return run_until([&] {
            module.tick({clock().monotonic(), clock().wall(), false});
            return !recorder_.messages_on(topic).empty();
        });
    }
    bool said_by(const std::string& edge_node_id) const {
        for (const auto& m : recorder_.messages()) {
            if (m.topic.ends_with("/" + edge_node_id) ||
                m.topic.find("/" + edge_node_id + "/") != std::string::npos)
                return true;
        }
        return false;
    }

    test::Mosquitto broker_;
    test::MqttRecorder recorder_;
};

TEST_F(SparkplugModuleTest, WithASingleUnitsRoleTheNodeConnectsAtStartAndIsBorn) {
    make_parts_of(nullptr);
    auto node = make("n1", *parts_);
    ASSERT_NE(node, nullptr);
    node->start(clock().monotonic());
    ASSERT_TRUE(seen(*node, "spBv1.0/plant1/NBIRTH/n1"));
    EXPECT_TRUE(node->node().born());
    node->stop();
}

TEST_F(SparkplugModuleTest, WithARoleItsSessionsFollowItConnectsOnlyOnceTheSessionOpens) {
    make_parts_of(std::make_unique<FollowingRole>());
    auto node = make("n1", *parts_);
    ASSERT_NE(node, nullptr);
    node->start(clock().monotonic());
    // A node of a single unit started after it is born; the one that follows its role is not.
    auto single_role = redundancy::make_role(config_, loop_.get_executor(), clock());
    NorthboundParts single_parts{loop_.get_executor(), clock(),
                                 *single_role,         south_->writes(),
                                 south_->exchanges(),  south_->north()};
    auto witness = make("n2", single_parts);
    witness->start(clock().monotonic());
    ASSERT_TRUE(seen(*witness, "spBv1.0/plant1/NBIRTH/n2"));
    EXPECT_FALSE(said_by("n1"));
    EXPECT_FALSE(node->node().born());
    EXPECT_FALSE(node->session_bd_seq().has_value());

    node->open_session(std::nullopt);
    ASSERT_TRUE(seen(*node, "spBv1.0/plant1/NBIRTH/n1"));
    EXPECT_TRUE(node->session_bd_seq().has_value());

    node->end_session();
    ASSERT_TRUE(seen(*node, "spBv1.0/plant1/NDEATH/n1"));
    EXPECT_FALSE(node->session_bd_seq().has_value());
    witness->stop();
    node->stop();
}

TEST_F(SparkplugModuleTest, TheBdSeqGoesOnFromTheStateDirectoryAfterARestart) {
    make_parts_of(nullptr);
    const auto bd_seq_of_nbirth = [&](std::size_t index) {
        const auto births = recorder_.messages_on("spBv1.0/plant1/NBIRTH/n1");
        org::eclipse::tahu::protobuf::Payload proto;
        EXPECT_TRUE(proto.ParseFromString(births.at(index).payload));
        EXPECT_EQ(proto.metrics(0).name(), "bdSeq");
        return proto.metrics(0).long_value();
    };
    for (std::size_t process = 0; process < 2; ++process) {
        auto node = make("n1", *parts_);
        ASSERT_NE(node, nullptr);
        node->start(clock().monotonic());
        ASSERT_TRUE(run_until(
            [&] { return recorder_.messages_on("spBv1.0/plant1/NBIRTH/n1").size() > process; }));
        node->stop();
    }
    EXPECT_EQ(bd_seq_of_nbirth(0), 0u);
    EXPECT_EQ(bd_seq_of_nbirth(1), 1u);  // the second process's first will
    std::ifstream kept(config_.gateway.state_dir + "/" + std::string(bd_seq_file_name));
    std::string line;
    EXPECT_TRUE(std::getline(kept, line));
    EXPECT_EQ(line, "1");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
