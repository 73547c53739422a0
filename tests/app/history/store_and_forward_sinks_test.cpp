// Store and forward with a second sink on a connection of its own (the Sparkplug node's):
// it replays once its own connection is up, again what its connection lost, and nothing that
// it published live or has no use for.

#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "tests/app/history/store_and_forward_rig.hpp"

namespace eip2mqtt::app::history {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using namespace test_rig;

/// A second northbound with a connection of its own (the Sparkplug node's), which the test
/// switches; its client holds what it was given until acknowledged, or drops it all when its
/// connection goes (session-bound).
struct OtherNorthbound {
    RecordingHistorySink sink;
    bool connected = false;
    std::size_t acknowledged = 0;  ///< of sink.replayed, in order
    std::size_t dropped = 0;       ///< of sink.replayed, lost with a connection
    LinkProbe link() {
        return {[this] { return connected; },
                [this] { return sink.replayed.size() - acknowledged - dropped; }};
    }
    void acknowledge_all(StoreAndForward& saf) {
        for (; acknowledged + dropped < sink.replayed.size(); ++acknowledged) {
            saf.on_acknowledged(sink, sink.replayed[acknowledged + dropped].token);
        }
    }
    std::vector<std::int64_t> values() const {
        std::vector<std::int64_t> out;
        for (const auto& r : sink.replayed) out.push_back(r.samples.at(0).second);
        return out;
    }
};

TEST_F(StoreAndForwardTest, AnotherSinkReplaysOnceItsOwnConnectionIsUp) {
    OtherNorthbound sparkplug;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 3; ++i) counter(i, 1000 + i);
    run_for(10ms);
    reconnect();  // the JSON tree's connection; the other is not back yet
    run_for(50ms);
    EXPECT_EQ(sink_.replayed.size(), 3u);
    EXPECT_TRUE(sparkplug.sink.replayed.empty());
    acknowledge_all();
    run_for(20ms);
    EXPECT_EQ(entries(), 3u) << "deleted before the other northbound had them";

    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(50ms);
    ASSERT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 2, 3}));
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(sparkplug.sink.replayed[i].timestamp_ms, sink_.replayed[i].timestamp_ms);
        EXPECT_EQ(sparkplug.sink.replayed[i].token, sink_.replayed[i].token);
    }
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_FALSE(saf_->stats().replaying);
    EXPECT_EQ(saf_->stats().replayed, 3u);
}

TEST_F(StoreAndForwardTest, WhatAnotherSinksConnectionLostGoesAgainOnItsNextConnection) {
    OtherNorthbound sparkplug;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 5; ++i) counter(i, 1000 + i);
    run_for(10ms);
    reconnect();
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(100ms);
    acknowledge_all();
    ASSERT_EQ(sparkplug.sink.replayed.size(), 5u);
    // Two acknowledged, then the connection goes with the other three.
    for (int i = 0; i < 2; ++i) {
        saf_->on_acknowledged(sparkplug.sink, sparkplug.sink.replayed[i].token);
    }
    sparkplug.acknowledged = 2;
    sparkplug.dropped = 3;
    sparkplug.connected = false;
    run_for(100ms);
    EXPECT_EQ(entries(), 3u);
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(100ms);
    EXPECT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 2, 3, 4, 5, 3, 4, 5}));
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
    EXPECT_EQ(sink_.replayed.size(), 5u);  // the JSON tree's replay is its own: nothing again
}

TEST_F(StoreAndForwardTest, WhatAnotherSinkPublishedLiveIsNotWaitedFor) {
    // The other northbound's connection stayed up through the first one's outage: it published
    // those samples live, and the journal does not keep them for it.
    OtherNorthbound sparkplug;
    sparkplug.connected = true;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    for (int i = 1; i <= 3; ++i) counter(i, 1000 + i);
    run_for(20ms);
    reconnect();
    run_for(50ms);
    acknowledge_all();
    run_for(100ms);
    EXPECT_EQ(entries(), 3u) << "a connection that went may not have been noticed yet";
    run_for(4s);
    EXPECT_TRUE(sparkplug.sink.replayed.empty());
    EXPECT_EQ(entries(), 0u);
}

TEST_F(StoreAndForwardTest, AnEntryASinkHasNoUseForIsNotWaitedFor) {
    OtherNorthbound sparkplug;
    sparkplug.sink.good_only = true;
    saf_->add_sink(sparkplug.sink, sparkplug.link());
    counter(1, 1001);
    counter(2, 1002, Quality::stale);
    counter(3, 1003);
    run_for(10ms);
    reconnect();
    sparkplug.connected = true;
    saf_->on_connected(sparkplug.sink, now_);
    run_for(50ms);
    EXPECT_EQ(sparkplug.values(), (std::vector<std::int64_t>{1, 3}));
    acknowledge_all();
    sparkplug.acknowledge_all(*saf_);
    run_for(20ms);
    EXPECT_EQ(entries(), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::history
