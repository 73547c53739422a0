// The JSON tree as a module, against a real Mosquitto: on each connection the exchanges'
// retained state and `_meta` are said again, then the connection's listeners run; the
// acknowledgements go to the takers in order (first ones first) until one takes the token; a
// reload that changes how tags are published republishes in applied(), not in apply(); and
// queue_room() reports the client's queue and mqtt.buffer_max_messages.

#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "tests/app/support/northbound_rig.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

adapters::mqtt::Message probe(const std::string& topic, std::uint64_t ack_token = 0) {
    adapters::mqtt::Message m;
    m.topic = topic;
    m.payload = "probe";
    m.qos = 1;
    m.ack_token = ack_token;
    return m;
}

class JsonTreeModuleTest : public test::NorthboundRig {
protected:
    /// The tree on the broker, knowing exchange "a" but deaf to its samples so far: what it
    /// says of them once connected is said by its republish alone.
    void make(const std::string& url) {
        config_ = config(url);
        make_parts();
        tree_ = std::make_unique<JsonTreeModule>(config_, *parts_);
        tree_->tree().exchanges_changed(south_->exchanges().running(), {});
        datagram(7, 1);
        south_->north().add(tree_->tree());
    }
    /// Runs the loop, ticking the tree, until `recorder` holds a message on `topic`.
    bool seen(test::MqttRecorder& recorder, const std::string& topic) {
        return run_until([&] {
            tree_->tick({clock().monotonic(), clock().wall(), false});
            return !recorder.messages_on(topic).empty();
        });
    }
    /// The topics `recorder` received, in order, from the `from`th on.
    static std::vector<std::string> topics(const test::MqttRecorder& recorder,
                                           std::size_t from = 0) {
        std::vector<std::string> out;
        const auto all = recorder.messages();
        for (auto i = from; i < all.size(); ++i) out.push_back(all[i].topic);
        return out;
    }
    void TearDown() override {
        if (tree_) tree_->stop();
    }

    test::Mosquitto broker_;
    std::unique_ptr<JsonTreeModule> tree_;
};

TEST_F(JsonTreeModuleTest, OnConnectionTheRetainedStateAndMetaGoThenTheListenersRun) {
    make(broker_.url());
    test::MqttRecorder recorder(broker_.url(), {"acme/a/#", "acme/probe"});
    int connections = 0;
    tree_->on_connected([&](core::MonoTime) {
        ++connections;
        tree_->client().publish(probe("acme/probe"));
    });
    tree_->start(clock().monotonic());
    ASSERT_TRUE(seen(recorder, "acme/probe"));
    ASSERT_TRUE(seen(recorder, "acme/a/_meta"));
    EXPECT_EQ(connections, 1);
    const auto value = recorder.last("acme/a/T");
    ASSERT_TRUE(value.has_value()) << "the retained state was not said again";
    EXPECT_NE(value->payload.find('7'), std::string::npos) << value->payload;
    // The listener's publication went behind the republished state, on the same lane.
    const auto order = topics(recorder);
    const auto state = std::find(order.begin(), order.end(), "acme/a/T");
    const auto listener = std::find(order.begin(), order.end(), "acme/probe");
    EXPECT_LT(state - order.begin(), listener - order.begin());
}

TEST_F(JsonTreeModuleTest, AcknowledgementsGoToTheTakersFirstOnesFirstUntilOneTakesIt) {
    make(broker_.url());
    std::map<std::uint64_t, std::vector<std::string>> offered;
    const auto taker = [&](std::string name, std::uint64_t takes) {
        return [&offered, name, takes](std::uint64_t token) {
            offered[token].push_back(name);
            return token == takes;
        };
    };
    tree_->take_acknowledgements(taker("journal", 2));
    tree_->take_acknowledgements(taker("last", 3));
    tree_->take_acknowledgements_first(taker("first", 1));
    tree_->start(clock().monotonic());
    ASSERT_TRUE(run_until([&] { return tree_->client().connected(); }));
    tree_->client().publish(probe("acme/probe/1", 1));
    tree_->client().publish(probe("acme/probe/2", 2));
    ASSERT_TRUE(run_until([&] { return offered.size() == 2; }))
        << offered.size() << " token(s) offered";
    EXPECT_EQ(offered[1], (std::vector<std::string>{"first"}));
    EXPECT_EQ(offered[2], (std::vector<std::string>{"first", "journal"}));
}

TEST_F(JsonTreeModuleTest, AChangedPublishSettingRepublishesInAppliedOnly) {
    make(broker_.url());
    test::MqttRecorder recorder(broker_.url(), {"acme/a/T", "acme/probe"});
    tree_->start(clock().monotonic());
    ASSERT_TRUE(seen(recorder, "acme/a/T"));
    auto next = config_;
    next.mqtt.retain = !config_.mqtt.retain;

    auto from = recorder.count();
    tree_->apply(next);
    tree_->client().publish(probe("acme/probe"));
    ASSERT_TRUE(run_until([&] { return recorder.count() > from; }));
    EXPECT_EQ(topics(recorder, from), std::vector<std::string>{"acme/probe"});

    from = recorder.count();
    tree_->applied();
    tree_->client().publish(probe("acme/probe"));
    ASSERT_TRUE(run_until([&] { return recorder.count() > from + 1; }));
    EXPECT_EQ(topics(recorder, from), (std::vector<std::string>{"acme/a/T", "acme/probe"}));
    EXPECT_EQ(recorder.last("acme/a/T")->retained, next.mqtt.retain);
}

TEST_F(JsonTreeModuleTest, QueueRoomReportsTheClientsQueueAndTheBufferBound) {
    make("tcp://127.0.0.1:1");  // never connects
    auto room = tree_->queue_room();
    ASSERT_TRUE(room.has_value());
    EXPECT_EQ(room->capacity, config_.mqtt.buffer_max_messages);
    EXPECT_FALSE(room->connected);
    const auto queued = room->queued;
    tree_->client().publish(probe("acme/probe"));
    tree_->client().publish(probe("acme/other"));
    EXPECT_EQ(tree_->queue_room()->queued, queued + 2);

    auto next = config_;
    next.mqtt.buffer_max_messages = config_.mqtt.buffer_max_messages + 17;
    tree_->apply(next);
    EXPECT_EQ(tree_->queue_room()->capacity, next.mqtt.buffer_max_messages);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
