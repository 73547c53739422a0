// SIGHUP with a file that removes a large plant: the exchanges stop and their retained topics
// are cleared in slices between which the loop goes on, so a kept produced exchange goes on
// sending and /healthz on answering while 102,000 topics are cleared; every one of them is
// cleared at the broker (before, the publish queue overflowed and dropped some), and a second
// SIGHUP during the clears is applied after them, so they do not clear what it starts.
//
// The test prints the longest gap between two produced datagrams during the reloads: before the
// apply was sliced, the loop stopped for all of it (0.3-0.5 s) in one go.

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>

#include "tests/integration/reload_large_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

/// The plant's topics all start so (`c0/T0`...); the other exchanges' do not.
constexpr std::string_view plant_prefix = "test/c";

bool in_plant(const Received& message) { return message.topic.starts_with(plant_prefix); }

const std::string removed = "configuration applied: 2 exchange(s) kept, 0 started, 1000 stopped";
const std::string restarted = "configuration applied: 2 exchange(s) kept, 1 started, 0 stopped";

/// Prints the gateway's own account of each reload: how long the loop applied, in how many
/// slices.
void print_reload_accounts(const std::string& log) {
    for (auto at = log.find("reload: parsed in"); at != std::string::npos;
         at = log.find("reload: parsed in", at + 1)) {
        std::printf("%s\n", log.substr(at, log.find('\n', at) - at).c_str());
    }
}

/// The second SIGHUP came while the first reload applied; it was applied after it.
void expect_the_second_reload_after_the_clears(const std::string& out) {
    const auto second_sighup = out.find("SIGHUP: reloading", out.find("SIGHUP: reloading") + 1);
    ASSERT_NE(out.find(removed), std::string::npos) << out;
    EXPECT_LT(second_sighup, out.find(removed)) << out;
    EXPECT_LT(out.find(removed), out.find(restarted)) << out;
    // 1,000 exchanges of 100 tags, a `_status` and a `_meta` each.
    EXPECT_NE(out.find("102000 retained topic(s) cleared"), std::string::npos) << out;
}

/// Each topic of the plant was cleared once, after the `before` messages there were before.
void expect_every_plant_topic_cleared(MqttRecorder& recorder, std::size_t before) {
    std::size_t cleared = 0;
    std::size_t next = before;
    EXPECT_TRUE(recorder.wait_for(
        [&](const std::vector<Received>& all) {
            for (; next < all.size(); ++next) {
                cleared += in_plant(all[next]) && all[next].payload.empty();
            }
            return cleared >= 102000;
        },
        60s))
        << cleared << " of 102000 cleared";
}

/// A new subscriber finds no retained topic of the plant but c0's, and those of `kept`.
template <class Topic>
void expect_retained_of_the_plant_only_c0s(const std::string& broker_url, const Topic& topic) {
    MqttRecorder fresh(broker_url, {topic("#")});
    fresh.publish(topic("marker"), "after the retained ones");
    ASSERT_TRUE(fresh.wait_for_message(topic("marker"), nullptr, 10s));
    std::vector<std::string> plant_retained;
    std::size_t kept_retained = 0;
    for (const auto& message : fresh.messages()) {
        if (!message.retained) continue;
        if (in_plant(message)) plant_retained.push_back(message.topic);
        kept_retained += message.topic.starts_with(topic("kept/"));
    }
    std::sort(plant_retained.begin(), plant_retained.end());
    EXPECT_EQ(plant_retained, (std::vector<std::string>{topic("c0/_meta"), topic("c0/_status")}));
    EXPECT_GT(kept_retained, 0u);
}

TEST_F(ReloadLargeTest, ProductionGoesOnWhileTheRetainedTopicsOf100000TagsAreCleared) {
    GatewayOptions options;
    // The recorder takes every publication (Mosquitto drops beyond 1,000 queued by default).
    options.broker.extra_config = "max_queued_messages 0\n";
    start_producing(plant(1000), options);
    // Every 50th exchange of the plant heard from: 2,000 tags with a retained value.
    for (int e = 0; e < 1000; e += 50) {
        send(DatagramBuilder("10.0.0.2", static_cast<std::uint32_t>(e + 100), 400)
                 .set("396.0", core::plan::TagType::dint, std::int64_t{e})
                 .build());
        ASSERT_TRUE(
            recorder_->wait_for_message(topic("c" + std::to_string(e) + "/T99"), nullptr, 10s));
    }
    // The plant's retained state is at the broker: its last status and description.
    ASSERT_TRUE(recorder_->wait_for_message(topic("c999/_status"), nullptr, 60s));
    ASSERT_TRUE(recorder_->wait_for_message(topic("c999/_meta"), nullptr, 60s));
    const auto before = recorder_->count();

    rewrite_exchanges(produced(capture_.port()) + kept());
    HealthPoller health(metrics_port_);
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("SIGHUP: reloading", 10s)) << gateway_->output();
    const auto started = ReloadClock::now();
    // The clears have begun: c0 comes back while they go on.
    ASSERT_TRUE(recorder_->wait_for_message(
        topic("c0/T0"), [](auto& p) { return p.empty(); }, 30s, before));
    rewrite_exchanges(produced(capture_.port()) + kept() + plant(1));
    gateway_->signal(SIGHUP);
    EXPECT_TRUE(gateway_->wait_for_output(restarted, 120s)) << gateway_->output();
    const auto ended = ReloadClock::now();
    health.stop();
    const auto inside = capture_.between(started + 100ms, ended - 100ms).size();
    std::printf(
        "reloads seen for %lld ms: %zu produced datagram(s) inside, the longest gap %lld ms\n",
        static_cast<long long>((ended - started) / 1ms), inside,
        static_cast<long long>(capture_.longest_gap(started, ended) / 1ms));
    print_reload_accounts(gateway_->output());
    EXPECT_GT(inside, 0u);
    EXPECT_TRUE(health.failures().empty()) << health.failures().front();

    expect_the_second_reload_after_the_clears(gateway_->output());

    // Each topic was cleared once, after what was there before.
    expect_every_plant_topic_cleared(*recorder_, before);
    EXPECT_TRUE(recorder_->wait_for_message(
        topic("c0/_status"), [](auto& p) { return !p.empty(); }, 10s, before));

    expect_retained_of_the_plant_only_c0s(
        broker_->url(), [this](const std::string& suffix) { return topic(suffix); });
    EXPECT_TRUE(gateway_->running());
}

TEST_F(ReloadLargeTest, AStopWhileAPlantsTopicsAreClearedEndsTheGatewayCleanly) {
    GatewayOptions options;
    options.broker.extra_config = "max_queued_messages 0\n";
    start_producing(plant(1000), options);
    const auto before = recorder_->count();
    rewrite_exchanges(produced(capture_.port()) + kept());
    gateway_->signal(SIGHUP);
    // The clears have begun (they take seconds at the broker's pace): the reload is under way.
    ASSERT_TRUE(recorder_->wait_for_message(
        topic("c0/T0"), [](auto& p) { return p.empty(); }, 30s, before));
    gateway_->signal(SIGTERM);
    EXPECT_EQ(gateway_->wait(60s), std::optional<int>(0)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("stopped:"), std::string::npos) << gateway_->output();
    // It stopped during the apply, which never ended.
    EXPECT_EQ(gateway_->output().find("configuration applied"), std::string::npos)
        << gateway_->output();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
