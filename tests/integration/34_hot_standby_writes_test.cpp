// Writes across a takeover of a hot-standby pair (docs/redundancy.md, "Writes"): two real
// gateways on one real Mosquitto, each reaching it through a proxy of its own that the test
// stalls, as behind a dead switch. A write the leader accepted and queued for its next datagram
// (a period of 20 s) is answered once, by one unit, even when the leader is cut off with it.

#include <nlohmann/json.hpp>

#include "tests/support/free_port.hpp"
#include "tests/support/pair_fixture.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

const std::string set_topic = "test/sp/SPEED_SP/set";
const std::string result_topic = "test/sp/SPEED_SP/set/result";

class CutOffWritesTest : public PairTest {
protected:
    void SetUp() override {
        broker_ = std::make_unique<Mosquitto>();
        recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
        for (const std::string id : {"gw-a", "gw-b"}) {
            proxies_[id] = std::make_unique<TcpProxy>(broker_->port());
            const auto url = "tcp://127.0.0.1:" + std::to_string(proxies_[id]->port());
            start_unit(id, pair_config(id, url, free_udp_port(), 20000));
        }
    }
    /// Waits for `id`'s metrics to count `count` writes left to the leader.
    bool left(const std::string& id, int count) {
        return recorder_
            ->wait_for_message(
                "test/_gateway/" + id + "/metrics",
                [&](const std::string& p) {
                    const auto j = json::parse(p, nullptr, false);
                    return j.is_object() && j.value("writes_left_to_leader", 0) == count;
                },
                10s)
            .has_value();
    }

    std::map<std::string, std::unique_ptr<TcpProxy>> proxies_;
};

TEST_F(CutOffWritesTest, AWriteQueuedOnALeaderCutOffIsAnsweredOnceByTheUnitThatTakesOver) {
    const auto leader = leader_beside_standby();
    ASSERT_FALSE(leader.empty()) << "nobody leads";
    const auto standby = other(leader);
    // Staged on the leader for its next datagram, 20 s away; the standby leaves it to the leader.
    recorder_->publish(set_topic, "3100");
    ASSERT_TRUE(left(standby, 1));

    const auto from = recorder_->count();
    proxies_[leader]->stall();
    // The leader's lease lapses with the write queued; the standby takes over and settles it:
    // never produced, so `standby`.
    ASSERT_TRUE(says(standby, "leader", from));
    ASSERT_TRUE(gateways_[leader]->wait_for_output("pair: standing by", 10s));
    const auto answer = recorder_->wait_for_message(result_topic, nullptr, 10s, from);
    ASSERT_TRUE(answer.has_value()) << "the queued write was never answered";
    EXPECT_EQ(json::parse(answer->payload), json({{"ok", false}, {"error", "standby"}}));

    // The path back: whatever the unit cut off said waited in its connection, and comes now.
    const auto back = recorder_->count();
    proxies_[leader]->resume();
    ASSERT_TRUE(
        recorder_
            ->wait_for_message(
                role_topic(leader), [](const std::string& p) { return p == "standby"; }, 10s, back)
            .has_value());
    // Its metrics published after it stepped down: whatever it said then came before them.
    ASSERT_TRUE(recorder_
                    ->wait_for_message(
                        "test/_gateway/" + leader + "/metrics",
                        [](const std::string& p) {
                            const auto j = json::parse(p, nullptr, false);
                            return j.is_object() && j.value("writes_cancelled", 0) == 1;
                        },
                        10s, back)
                    .has_value());
    EXPECT_EQ(recorder_->messages_on(result_topic).size(), 1u)
        << "the write was answered by both units";
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
