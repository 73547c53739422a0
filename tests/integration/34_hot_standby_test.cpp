// A hot-standby pair (docs/redundancy.md): two real gateways on one real Mosquitto, both with
// the same produced exchange sent to the test's socket. One leads; when it is killed, stopped
// and resumed, or cut off from the broker, the other takes over, and the capture shows the two
// never produced at once: each unit numbers its datagrams with its own request ids, so the capture
// is one run of consecutive ids per leadership (never more runs than `leader` said on the role
// topics), and two producers at once would cut it into many.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/pair_fixture.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/tcp_proxy.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

const std::string leader_topic = "test/_gateway/_pair/turbine/leader";

class HotStandbyTest : public PairTest {
protected:
    void SetUp() override {
        broker_ = std::make_unique<Mosquitto>();
        before_start();
        recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
        for (const std::string id : {"gw-a", "gw-b"}) {
            configs_[id] = pair_config(id, broker_url(id), free_udp_port(), period_ms());
            start(id);
        }
    }

    virtual std::uint32_t period_ms() const { return 50; }
    virtual void before_start() {}
    virtual std::string broker_url(const std::string&) const { return broker_->url(); }

    void start(const std::string& id) { start_unit(id, configs_[id]); }
    /// The leader record with `id` (after message `from`), as JSON.
    json record_of(const std::string& id, std::size_t from = 0) {
        const auto message = recorder_->wait_for_message(
            leader_topic,
            [&](const std::string& p) {
                const auto j = json::parse(p, nullptr, false);
                return j.is_object() && j.value("id", "") == id;
            },
            30s, from);
        return message ? json::parse(message->payload) : json();
    }
    /// Receives `count` more datagrams into captured_; false when they did not come.
    bool capture(std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            const auto bytes = capture_.receive(10s);
            if (!bytes) return false;
            const auto decoded = core::wire::decode_datagram(*bytes);
            if (!decoded.ok()) return false;
            captured_.push_back(decoded.value().header.request_id);
        }
        return true;
    }
    /// How many runs of consecutive request ids the capture holds: one per producer that
    /// produced alone; two producers at once make one per datagram, nearly.
    std::size_t runs() const {
        std::size_t out = captured_.empty() ? 0 : 1;
        for (std::size_t i = 1; i < captured_.size(); ++i) {
            if (captured_[i] != static_cast<std::uint16_t>(captured_[i - 1] + 1)) ++out;
        }
        return out;
    }
    /// How many times a unit said `leader` on its role topic: a loaded machine may see a unit
    /// fenced and a takeover more than the test caused, each one a leadership of its own.
    static std::size_t leaderships_in(const std::vector<Received>& all) {
        std::size_t out = 0;
        for (const auto& m : all) {
            out += (m.topic == role_topic("gw-a") || m.topic == role_topic("gw-b")) &&
                   m.payload == "leader";
        }
        return out;
    }
    /// True once the role topics hold a leadership for each run of the capture. A new leader's
    /// datagrams can reach the test before its `leader` has crossed the broker, so the test
    /// waits for it; two producers at once cut the capture into more runs than ever come.
    bool leaderships_cover_runs() {
        const auto needed = runs();
        return recorder_->wait_for(
            [&](const std::vector<Received>& all) { return leaderships_in(all) >= needed; }, 10s);
    }
    /// The last leader record of `id` so far, as JSON: the epoch of the lease it holds.
    json last_record_of(const std::string& id) const {
        json out;
        for (const auto& m : recorder_->messages_on(leader_topic)) {
            const auto j = json::parse(m.payload, nullptr, false);
            if (j.is_object() && j.value("id", "") == id) out = j;
        }
        return out;
    }
    /// The pair once settled: who leads, who stands by, the lease's epoch, and 20 datagrams
    /// captured; `leader` empty (the reason in `why`) when it did not settle. On a loaded
    /// machine the lead may pass while it settles (two claims at once, a leader fenced after a
    /// stall): the leader is the one leading beside a standby then, its epoch that of its last
    /// record.
    struct Settled {
        std::string leader;
        std::string standby;
        int epoch = 0;
        std::string why;
    };
    Settled settle() {
        if (leader_beside_standby().empty()) return {"", "", 0, "nobody leads"};
        if (!capture(20)) return {"", "", 0, "the leader's first 20 datagrams did not come"};
        if (!leaderships_cover_runs()) return {"", "", 0, "the standby produced beside the leader"};
        Settled out{leader_beside_standby()};
        if (out.leader.empty()) return {"", "", 0, "the pair never stood as leader and standby"};
        out.standby = other(out.leader);
        out.epoch = last_record_of(out.leader).value("epoch", 0);
        return out;
    }
    std::map<std::string, std::string> configs_;
    std::vector<std::uint16_t> captured_;
};

TEST_F(HotStandbyTest, TheStandbyTakesOverFromAKilledLeaderAndNeverProducesBesideIt) {
    const auto settled = settle();
    ASSERT_FALSE(settled.leader.empty()) << settled.why;
    const auto& leader = settled.leader;
    const auto& standby = settled.standby;
    const auto epoch = settled.epoch;
    ASSERT_GE(epoch, 1);

    const auto from = recorder_->count();
    gateways_[leader]->signal(SIGKILL);
    ASSERT_TRUE(gateways_[leader]->wait(10s).has_value());
    ASSERT_TRUE(says(standby, "leader", from));
    const auto record = record_of(standby, from);
    EXPECT_EQ(record.value("epoch", 0), epoch + 1);
    EXPECT_EQ(schema_problem(schema_file("leader.json"), record.dump()), "");
    // What the killed leader sent before it died, then the new leader's alone.
    ASSERT_TRUE(capture(40));
    EXPECT_GE(runs(), 2u);
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
}

TEST_F(HotStandbyTest, AKilledLeaderRestartedStandsByBesideTheNewOne) {
    const auto leader = leader_beside_standby();
    ASSERT_FALSE(leader.empty()) << "nobody leads";
    const auto standby = other(leader);
    const auto from = recorder_->count();
    gateways_[leader]->signal(SIGKILL);
    ASSERT_TRUE(gateways_[leader]->wait(10s).has_value());
    ASSERT_TRUE(says(standby, "leader", from));

    const auto restarted = recorder_->count();
    start(leader);
    // A write as soon as the restarted unit is online, before it may have read who leads:
    // answered once, by the leader.
    ASSERT_TRUE(recorder_
                    ->wait_for_message(
                        "test/_gateway/" + leader + "/state",
                        [](const std::string& p) { return p == "online"; }, 30s, restarted)
                    .has_value());
    recorder_->publish("test/sp/SPEED_SP/set", "3100");
    ASSERT_TRUE(says(leader, "standby", restarted));
    const auto epoch = record_of(standby, restarted).value("epoch", 0);
    ASSERT_TRUE(capture(40));
    const auto result =
        recorder_->wait_for_message("test/sp/SPEED_SP/set/result", nullptr, 10s, restarted);
    ASSERT_TRUE(result.has_value()) << "the write was never answered";
    EXPECT_EQ(json::parse(result->payload), json({{"ok", true}}));
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
    // The new leader kept the lead: its renewals go on with its epoch, and the restarted unit
    // never claimed it.
    EXPECT_EQ(record_of(standby, recorder_->count() - 1).value("epoch", 0), epoch);
    EXPECT_FALSE(recorder_
                     ->wait_for_message(
                         role_topic(leader), [](const std::string& p) { return p == "leader"; },
                         0ms, restarted)
                     .has_value());
    EXPECT_EQ(recorder_->messages_on("test/sp/SPEED_SP/set/result").size(), 1u);
}

TEST_F(HotStandbyTest, ALeaderResumedAfterSigstopIsFencedAndStandsBy) {
    const auto settled = settle();
    ASSERT_FALSE(settled.leader.empty()) << settled.why;
    const auto& leader = settled.leader;
    const auto& standby = settled.standby;
    const auto epoch = settled.epoch;

    const auto from = recorder_->count();
    gateways_[leader]->signal(SIGSTOP);
    ASSERT_TRUE(says(standby, "leader", from));
    EXPECT_EQ(record_of(standby, from).value("epoch", 0), epoch + 1);
    ASSERT_TRUE(capture(20));

    const auto resumed = recorder_->count();
    gateways_[leader]->signal(SIGCONT);
    ASSERT_TRUE(says(leader, "standby", resumed));
    // Whatever the resumed unit's timers had due, none of it left: the new leader's run goes on.
    ASSERT_TRUE(capture(40));
    EXPECT_GE(runs(), 2u);
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
    // The topic holds the new leader's lease, renewed since.
    const auto last = recorder_->last(leader_topic);
    ASSERT_TRUE(last.has_value());
    const auto record = json::parse(last->payload, nullptr, false);
    ASSERT_TRUE(record.is_object()) << last->payload;
    EXPECT_EQ(record.value("id", ""), standby);
}

TEST_F(HotStandbyTest, OnlyTheLeaderAnswersAWrite) {
    const auto leader = leader_beside_standby();
    ASSERT_FALSE(leader.empty()) << "nobody leads";
    const auto standby = other(leader);
    for (int i = 0; i < 2; ++i) {
        const auto from = recorder_->count();
        recorder_->publish("test/sp/SPEED_SP/set", std::to_string(3100 + i));
        ASSERT_TRUE(recorder_->wait_for_message("test/sp/SPEED_SP/set/result", nullptr, 10s, from)
                        .has_value());
    }
    // The standby left both to the leader, and says so in its metrics.
    ASSERT_TRUE(recorder_
                    ->wait_for_message(
                        "test/_gateway/" + standby + "/metrics",
                        [](const std::string& p) {
                            return json::parse(p).value("writes_left_to_leader", 0) == 2;
                        },
                        10s)
                    .has_value());
    for (const auto& m : recorder_->messages_on("test/sp/SPEED_SP/set/result")) {
        EXPECT_EQ(json::parse(m.payload), json({{"ok", true}})) << m.payload;
    }
}

/// A period so long that a write accepted by the leader waits in its queue through a takeover.
class SlowHotStandbyTest : public HotStandbyTest {
protected:
    std::uint32_t period_ms() const override { return 20000; }
};

TEST_F(SlowHotStandbyTest, AWriteQueuedOnALeaderThatStepsDownIsAnsweredStandbyNeverApplied) {
    const auto leader = leader_beside_standby();
    ASSERT_FALSE(leader.empty()) << "nobody leads";
    const auto standby = other(leader);
    // Staged on the leader for its next datagram, 20 s away; the standby leaves it to the leader.
    recorder_->publish("test/sp/SPEED_SP/set", "3100");
    ASSERT_TRUE(recorder_
                    ->wait_for_message(
                        "test/_gateway/" + standby + "/metrics",
                        [](const std::string& p) {
                            return json::parse(p).value("writes_left_to_leader", 0) == 1;
                        },
                        10s)
                    .has_value());

    const auto from = recorder_->count();
    gateways_[leader]->signal(SIGSTOP);
    ASSERT_TRUE(says(standby, "leader", from));
    gateways_[leader]->signal(SIGCONT);
    ASSERT_TRUE(says(leader, "standby", from));
    const auto result = recorder_->wait_for_message("test/sp/SPEED_SP/set/result", nullptr, 30s);
    ASSERT_TRUE(result.has_value()) << "the queued write was never answered";
    EXPECT_EQ(json::parse(result->payload), json({{"ok", false}, {"error", "standby"}}));
    EXPECT_EQ(recorder_->messages_on("test/sp/SPEED_SP/set/result").size(), 1u);
}

/// Each unit reaches the broker through a proxy of its own, which the test stalls: the leader cut
/// off from the broker, as behind a dead switch, must stop producing before the standby, which
/// hears it no more, takes over.
class CutOffHotStandbyTest : public HotStandbyTest {
protected:
    void before_start() override {
        for (const std::string id : {"gw-a", "gw-b"}) {
            proxies_[id] = std::make_unique<TcpProxy>(broker_->port());
        }
    }
    std::string broker_url(const std::string& id) const override {
        return "tcp://127.0.0.1:" + std::to_string(proxies_.at(id)->port());
    }
    std::size_t results_after(std::size_t from) const {
        std::size_t out = 0;
        const auto all = recorder_->messages();
        for (auto i = from; i < all.size(); ++i) out += all[i].topic == write_result;
        return out;
    }

    static std::string claiming(int epoch) {
        return "pair: claiming the lead, epoch " + std::to_string(epoch) + "\n";
    }

    const std::string write_result = "test/sp/SPEED_SP/set/result";
    std::map<std::string, std::unique_ptr<TcpProxy>> proxies_;
};

TEST_F(CutOffHotStandbyTest, ALeaderCutOffFromTheBrokerStopsBeforeTheStandbyTakesOver) {
    const auto settled = settle();
    ASSERT_FALSE(settled.leader.empty()) << settled.why;
    const auto& leader = settled.leader;
    const auto& standby = settled.standby;
    const auto epoch = settled.epoch;

    const auto from = recorder_->count();
    proxies_[leader]->stall();
    // A write in flight at the cut: the leader cannot hear it; the standby leaves it to the
    // leader, then settles it as it leads. Answered once either way.
    recorder_->publish("test/sp/SPEED_SP/set", "3100");
    ASSERT_TRUE(says(standby, "leader", from));
    EXPECT_EQ(record_of(standby, from).value("epoch", 0), epoch + 1);
    ASSERT_TRUE(recorder_->wait_for_message(write_result, nullptr, 30s, from).has_value());
    // The cut-off leader's datagrams stopped before the new leader's began: one run each.
    ASSERT_TRUE(capture(40));
    EXPECT_GE(runs(), 2u);
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
    // Cut off, it claims into a connection that carries nothing. Time for a second claim of a
    // higher epoch, as a unit made before claims stopped behind one never acknowledged (on a
    // busy machine it had the time, and took the lead back once the path came back).
    gateways_[leader]->wait_for_output(claiming(epoch + 2), 3s);

    const auto back = recorder_->count();
    proxies_[leader]->resume();
    ASSERT_TRUE(says(leader, "standby", from)) << "the unit cut off never said it stood by";
    ASSERT_TRUE(record_of(standby, back).is_object());
    ASSERT_TRUE(capture(40));
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
    // The lead stayed with the new leader, and the write was answered once, by one unit.
    EXPECT_FALSE(
        recorder_
            ->wait_for_message(
                role_topic(leader), [](const std::string& p) { return p == "leader"; }, 0ms, back)
            .has_value());
    EXPECT_EQ(results_after(from), 1u);
}

TEST_F(CutOffHotStandbyTest, AStandbyCutOffFromTheBrokerNeverDeposesTheLeaderOnceThePathIsBack) {
    const auto settled = settle();
    ASSERT_FALSE(settled.leader.empty()) << settled.why;
    const auto& leader = settled.leader;
    const auto& standby = settled.standby;
    const auto epoch = settled.epoch;

    proxies_[standby]->stall();
    // It hears the leader no more and claims: the claim waits in its connection's buffers. Time
    // for a second one, of a higher epoch, as it made before.
    ASSERT_TRUE(gateways_[standby]->wait_for_output(claiming(epoch + 1), 10s));
    gateways_[standby]->wait_for_output(claiming(epoch + 2), 3s);
    const auto back = recorder_->count();
    proxies_[standby]->resume();
    // What it claimed reaches the broker, and the leader: which leads on and renews over it.
    const auto is_claim_of = [](const std::string& id) {
        return [id](const std::string& p) {
            const auto j = json::parse(p, nullptr, false);
            return j.is_object() && j.value("id", "") == id && j.value("claim", false);
        };
    };
    ASSERT_TRUE(recorder_->wait_for_message(leader_topic, is_claim_of(standby), 10s, back));
    EXPECT_FALSE(says(leader, "standby", back, 3s)) << "a claim made cut off deposed the leader";
    EXPECT_FALSE(says(standby, "leader", back, 0ms));
    const auto renewed = record_of(leader, recorder_->count() - 1);
    EXPECT_GE(renewed.value("epoch", 0), epoch + 1);
    EXPECT_FALSE(renewed.value("claim", false));
    ASSERT_TRUE(capture(40));
    EXPECT_TRUE(leaderships_cover_runs()) << "the standby produced beside the leader";
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
