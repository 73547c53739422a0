// make_northbounds: which modules a configuration makes, in which order (the JSON tree always
// and first, store and forward with mqtt.store_and_forward, the Sparkplug node with
// `sparkplug:`), and which of them hear the exchanges through the fan-out: the tree unless
// `sparkplug.uns: false`, the journal with store and forward. No broker: every connection is
// down, so what the tree is handed waits in its client's queue, and the journal keeps it.

#include "eip2mqtt/app/northbound/northbounds.hpp"

#include <gtest/gtest.h>

#include <string>
#include <typeinfo>
#include <vector>

#include "eip2mqtt/app/history/store_and_forward_module.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"
#include "tests/app/support/northbound_rig.hpp"

namespace eip2mqtt::app::northbound {
namespace EIP2MQTT_THIS_FILE {

constexpr auto store_and_forward_on = "  store_and_forward:\n    enabled: true\n";
constexpr auto sparkplug_on = "sparkplug:\n  group_id: plant1\n";
constexpr auto sparkplug_alone = "sparkplug:\n  group_id: plant1\n  uns: false\n";

class NorthboundsTest : public test::NorthboundRig {
protected:
    /// The northbounds of `extra` (under mqtt:) and `sections`, then the exchanges run.
    void make(const std::string& extra, const std::string& sections = "") {
        config_ = config("tcp://127.0.0.1:1", extra, sections);
        make_parts(nullptr, false);
        north_ = make_northbounds(config_, *parts_);
        apply_plans();
    }
    /// The kind of each module, in order.
    std::vector<std::string> kinds() const {
        std::vector<std::string> out;
        for (const auto& module : north_.modules) {
            const auto* m = module.get();
            if (dynamic_cast<const json_tree::JsonTreeModule*>(m))
                out.push_back("tree");
            else if (dynamic_cast<const history::StoreAndForwardModule*>(m))
                out.push_back("store and forward");
            else if (dynamic_cast<const sparkplug::SparkplugModule*>(m))
                out.push_back("node");
            else
                out.push_back(typeid(*m).name());
        }
        return out;
    }
    /// What the tree's client holds, for it, after one sample of exchange "a".
    std::uint64_t queued_by_a_sample() {
        const auto before = north_.tree->client().stats().queued;
        datagram(7, 1);
        return north_.tree->client().stats().queued - before;
    }
    void TearDown() override {
        for (auto it = north_.modules.rbegin(); it != north_.modules.rend(); ++it) (*it)->stop();
    }

    Northbounds north_;
};

using Kinds = std::vector<std::string>;

TEST_F(NorthboundsTest, TheTreeAloneHearsTheExchanges) {
    make("");
    EXPECT_EQ(kinds(), Kinds{"tree"});
    ASSERT_NE(north_.tree, nullptr);
    EXPECT_EQ(north_.tree, north_.modules[0].get());
    EXPECT_EQ(north_.node, nullptr);
    EXPECT_GT(queued_by_a_sample(), 0u);
}

TEST_F(NorthboundsTest, StoreAndForwardComesAfterTheTreeAndJournalsTheSamples) {
    make(store_and_forward_on);
    EXPECT_EQ(kinds(), (Kinds{"tree", "store and forward"}));
    auto& history = dynamic_cast<history::StoreAndForwardModule&>(*north_.modules[1]);
    // The connection is down: the journal keeps the sample for its replay.
    EXPECT_GT(queued_by_a_sample(), 0u);
    ASSERT_TRUE(run_until([&] {
        history.tick({clock().monotonic(), clock().wall(), false});
        return history.store().stats().journal.entries == 1;
    }));
}

TEST_F(NorthboundsTest, SparkplugAddsTheNodeLastAndKeepsTheTreeAsTheNamespace) {
    make(store_and_forward_on, sparkplug_on);
    EXPECT_EQ(kinds(), (Kinds{"tree", "store and forward", "node"}));
    ASSERT_NE(north_.node, nullptr);
    EXPECT_EQ(north_.node, north_.modules[2].get());
    EXPECT_EQ(north_.tree, north_.modules[0].get());
}

TEST_F(NorthboundsTest, WithSparkplugAsTheNamespaceTheTreeHearsNoExchange) {
    make("", sparkplug_alone);
    EXPECT_EQ(kinds(), (Kinds{"tree", "node"}));
    EXPECT_EQ(queued_by_a_sample(), 0u);
}

TEST_F(NorthboundsTest, WithSparkplugBesideItTheTreeStillHearsTheExchanges) {
    make("", sparkplug_on);
    EXPECT_EQ(kinds(), (Kinds{"tree", "node"}));
    EXPECT_GT(queued_by_a_sample(), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound
