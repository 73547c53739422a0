// make_store_and_forward: nothing without mqtt.store_and_forward, nothing (and an error logged)
// when the journal cannot be opened; otherwise the module joins the JSON tree's connection: a
// sample journaled while it is down is replayed on `_history` once it connects (a real
// Mosquitto), and the broker's acknowledgement of the replay reaches the journal.

#include "eip2mqtt/app/history/store_and_forward_module.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"
#include "tests/app/support/northbound_rig.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::app::history {
namespace EIP2MQTT_THIS_FILE {

constexpr auto store_and_forward_on = "  store_and_forward:\n    enabled: true\n";

class StoreAndForwardModuleTest : public test::NorthboundRig {
protected:
    void make(const std::string& url, const std::string& extra) {
        config_ = config(url, extra);
        make_parts();
        tree_ = std::make_unique<northbound::json_tree::JsonTreeModule>(config_, *parts_);
    }
    void TearDown() override {
        if (tree_) tree_->stop();
    }

    std::unique_ptr<northbound::json_tree::JsonTreeModule> tree_;
};

TEST_F(StoreAndForwardModuleTest, WithoutStoreAndForwardThereIsNone) {
    make("tcp://127.0.0.1:1", "");
    EXPECT_EQ(make_store_and_forward(config_, *parts_, *tree_), nullptr);
    EXPECT_FALSE(std::filesystem::exists(dir_ / "state" / "history.sqlite"));
}

TEST_F(StoreAndForwardModuleTest, AJournalThatCannotBeOpenedIsLoggedAndLeftOut) {
    make("tcp://127.0.0.1:1", store_and_forward_on);
    // A state directory under a plain file cannot be made, by root either.
    std::ofstream(dir_ / "file") << "not a directory";
    config_.gateway.state_dir = (dir_ / "file" / "state").string();
    test::LogCapture log;
    EXPECT_EQ(make_store_and_forward(config_, *parts_, *tree_), nullptr);
    const auto lines = log.lines();
    const auto off = std::find_if(lines.begin(), lines.end(), [](const std::string& line) {
        return line.starts_with("store and forward is off: the journal ");
    });
    ASSERT_NE(off, lines.end());
    EXPECT_NE(off->find("gateway.state_dir"), std::string::npos) << *off;
}

TEST_F(StoreAndForwardModuleTest, ItTakesTheSectionsRateAndFsyncAndKeepsTheDefaultReplayBudget) {
    make("tcp://127.0.0.1:1",
         std::string(store_and_forward_on) + "    replay_rate: 5000\n    fsync_interval_ms: 250\n");
    auto module = make_store_and_forward(config_, *parts_, *tree_);
    ASSERT_NE(module, nullptr);
    const auto& options = module->store().options();
    EXPECT_EQ(options.replay_rate, 5000u);
    EXPECT_EQ(options.fsync_interval, std::chrono::milliseconds(250));
    EXPECT_EQ(options.clock, &clock());
    // A tick's replay gets its loop time: with none, one entry a tick went (about 100 a second
    // at any replay_rate).
    EXPECT_EQ(options.replay_budget, StoreAndForwardOptions{}.replay_budget);
    EXPECT_GT(options.replay_budget.count(), 0);
}

TEST_F(StoreAndForwardModuleTest, ItJoinsTheTreesConnectionItsReplayAndItsAcknowledgements) {
    test::Mosquitto broker;
    make(broker.url(), store_and_forward_on);
    auto module = make_store_and_forward(config_, *parts_, *tree_);
    ASSERT_NE(module, nullptr);
    EXPECT_TRUE(std::filesystem::exists(dir_ / "state" / "history.sqlite"));
    // As its maker joins them: the journal before the tree.
    south_->north().add(module->store());
    south_->north().add(tree_->tree());
    south_->north().exchanges_changed(south_->exchanges().running(), {});

    datagram(7, 1);  // the tree's connection is down: journaled
    const auto tick = [&] {
        const TickTimes times{clock().monotonic(), clock().wall(), false};
        module->tick(times);
        tree_->tick(times);
    };
    ASSERT_TRUE(run_until([&] {
        tick();
        return module->store().stats().journal.entries == 1;
    }));
    test::MqttRecorder recorder(broker.url(), {"acme/a/_history"});
    tree_->start(clock().monotonic());
    ASSERT_TRUE(run_until([&] {
        tick();
        return !recorder.messages_on("acme/a/_history").empty();
    }));
    EXPECT_NE(recorder.messages_on("acme/a/_history")[0].payload.find('7'), std::string::npos);
    // The broker's acknowledgement of the replayed entry was taken by the journal.
    ASSERT_TRUE(run_until([&] {
        tick();
        return module->store().stats().replayed == 1;
    }));
    MetricsSources sources{south_->exchanges().datagram_counters(), south_->writes().counters()};
    module->add_metrics(sources);
    ASSERT_NE(sources.history, nullptr);
    EXPECT_EQ(sources.history->replayed, 1u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::history
