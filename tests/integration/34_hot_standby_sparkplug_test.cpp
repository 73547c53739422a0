// A hot-standby pair is one Sparkplug B edge node (docs/redundancy.md): two real gateways on
// one real Mosquitto, every Sparkplug message read by Eclipse Tahu's decoder. Only the leader
// holds the node's session; the standby does not even connect it. When the leader is killed,
// a host sees its session die (the NDEATH will, with the session's bdSeq), then the new
// leader's session, with another bdSeq, its every device born, then data.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/pair_fixture.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

const std::string leader_topic = "test/_gateway/_pair/turbine/leader";
/// The edge node is the pair's: both units are `turbine`.
std::string node_topic(const std::string& type) { return "spBv1.0/plant1/" + type + "/turbine"; }
std::string device_topic(const std::string& type, const std::string& device) {
    return node_topic(type) + "/" + device;
}

class HotStandbySparkplugTest : public PairTest {
protected:
    void SetUp() override {
        broker_ = std::make_unique<Mosquitto>();
        recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
        // Never stale (timeout 0): the consumed device stays up through the takeover.
        const auto plant = ExchangeYaml::consume("plant", "10.9.9.9", 1)
                               .length(4)
                               .period_ms(100)
                               .timeout_ms(0)
                               .tag("PV", "0.0", "dint")
                               .str();
        start_units([&](const std::string& id, std::uint16_t port) {
            return pair_config(id, broker_->url(), port, 50, "sparkplug: { group_id: plant1 }\n",
                               plant);
        });
    }

    /// A datagram of `plant` to every unit still running, as a multicast group both join.
    void send_plant(std::uint16_t request_id, std::int64_t pv) {
        const auto bytes = DatagramBuilder("10.9.9.9", 1, 4)
                               .request_id(request_id)
                               .set("0.0", core::plan::TagType::dint, core::plan::Value{pv})
                               .build();
        for (const auto& [id, gateway] : gateways_) {
            if (gateway) capture_.send_to(ports_.at(id), bytes);
        }
    }
    /// The index of the first message on `topic` at `from` or after; waits for it.
    std::optional<std::size_t> index_of(const std::string& topic, std::size_t from) {
        std::optional<std::size_t> found;
        recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                for (auto i = from; i < all.size() && !found; ++i) {
                    if (all[i].topic == topic) found = i;
                }
                return found.has_value();
            },
            30s);
        return found;
    }
    /// The leader record of `id` that carries a bdSeq, read after message `from`.
    json renewal_with_bd_seq(const std::string& id, std::size_t from = 0) {
        const auto message = recorder_->wait_for_message(
            leader_topic,
            [&](const std::string& p) {
                const auto j = json::parse(p, nullptr, false);
                return j.is_object() && j.value("id", "") == id && j.contains("bd_seq");
            },
            30s, from);
        if (!message) return json();
        EXPECT_EQ(schema_problem(schema_file("leader.json"), message->payload), "");
        return json::parse(message->payload);
    }

    /// The leader, once the other unit stands by and the leader's session is under way: its
    /// NBIRTH, `plant` born with a first datagram, and a renewal carrying the session's bdSeq,
    /// which the standby hears as well. An empty leader, and a failure, when that did not come.
    std::pair<std::string, json> leading_session() {
        const auto leader = leader_beside_standby();
        if (leader.empty() || !index_of(node_topic("NBIRTH"), 0)) {
            ADD_FAILURE() << "no leader with a Sparkplug session beside a standby";
            return {};
        }
        send_plant(1, 10);
        auto renewal = renewal_with_bd_seq(leader);
        if (!index_of(device_topic("DBIRTH", "plant"), 0) || !renewal.is_object()) {
            ADD_FAILURE() << "no DBIRTH, or no renewal with a bdSeq";
            return {};
        }
        return {leader, std::move(renewal)};
    }
    /// How many times a unit said `leader` on its role topic since message `from`.
    std::size_t leaderships(std::size_t from) const {
        const auto all = recorder_->messages();
        std::size_t out = 0;
        for (auto i = from; i < all.size(); ++i) {
            const bool role =
                all[i].topic == role_topic("gw-a") || all[i].topic == role_topic("gw-b");
            if (role && all[i].payload == "leader") ++out;
        }
        return out;
    }
};

/// The bdSeq metric of an NBIRTH or NDEATH, as Tahu reads it (a string: it is an Int64).
std::string bd_seq_of(const std::string& payload) {
    const auto decoded = tahu_decode(payload);
    for (const auto& metric : decoded.value("metrics", json::array())) {
        if (metric.value("name", "") == "bdSeq") return metric.value("value", "");
    }
    ADD_FAILURE() << "no bdSeq";
    return {};
}

TEST_F(HotStandbySparkplugTest, OnlyTheLeaderIsTheEdgeNodeAndATakeoverIsANewSessionOfIt) {
    const auto [leader, renewal] = leading_session();
    ASSERT_FALSE(leader.empty());
    const auto standby = other(leader);
    send_plant(2, 11);
    ASSERT_TRUE(index_of(device_topic("DDATA", "plant"), 0));

    const auto killed = recorder_->count();
    gateways_[leader]->signal(SIGKILL);
    ASSERT_TRUE(gateways_[leader]->wait(10s).has_value());
    const auto death = index_of(node_topic("NDEATH"), killed);
    ASSERT_TRUE(death) << "the killed leader's will said nothing";
    ASSERT_TRUE(says(standby, "leader", killed));
    const auto birth = index_of(node_topic("NBIRTH"), killed);
    ASSERT_TRUE(birth);
    ASSERT_TRUE(index_of(device_topic("DBIRTH", "plant"), *birth));
    ASSERT_TRUE(index_of(device_topic("DBIRTH", "sp"), *birth));
    const auto data_from = recorder_->count();
    send_plant(3, 12);
    ASSERT_TRUE(index_of(device_topic("DDATA", "plant"), data_from));
    EXPECT_EQ(renewal_with_bd_seq(standby, killed).value("epoch", 0),
              renewal.value("epoch", 0) + 1);

    const auto all = recorder_->messages();
    const auto is = [&](std::size_t i, const std::string& type) {
        return all[i].topic == node_topic(type);
    };
    // The old session died before the new one began, and nothing was said as the edge node in
    // between: the standby said nothing before it led.
    EXPECT_LT(*death, *birth);
    for (auto i = *death + 1; i < *birth; ++i) {
        EXPECT_NE(all[i].topic.rfind("spBv1.0/", 0), 0u) << all[i].topic;
    }
    std::optional<std::size_t> old_birth;
    std::size_t new_births = 0;
    std::size_t deaths_after = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (is(i, "NBIRTH") && i < killed) old_birth = i;
        if (is(i, "NBIRTH") && i >= killed) ++new_births;
        if (is(i, "NDEATH") && i > *death) ++deaths_after;
    }
    // A machine loaded enough may fence the new leader and see it take over again: a session
    // each time. Otherwise, one session of the new leader, never ended.
    if (leaderships(killed) == 1) {
        EXPECT_EQ(new_births, 1u);
        EXPECT_EQ(deaths_after, 0u);
    }
    // The old session's death carries its bdSeq; the new one's is the next.
    ASSERT_TRUE(old_birth);
    const auto old_bd_seq = bd_seq_of(all[*old_birth].payload);
    EXPECT_EQ(bd_seq_of(all[*death].payload), old_bd_seq);
    EXPECT_EQ(old_bd_seq, std::to_string(renewal.value("bd_seq", -1)));
    const auto new_bd_seq = bd_seq_of(all[*birth].payload);
    EXPECT_NE(new_bd_seq, old_bd_seq);
    EXPECT_EQ(new_bd_seq, std::to_string((renewal.value("bd_seq", 0) + 1) % 256));
    // The standby connected the node's session only once it led.
    const auto log = gateways_[standby]->output();
    const auto led = log.find("pair: leading");
    const auto connected = log.find("MQTT (Sparkplug) connected");
    ASSERT_NE(connected, std::string::npos) << log;
    EXPECT_LT(led, connected) << log;
}

TEST_F(HotStandbySparkplugTest, ALeaderThatStepsDownEndsItsSessionWithItsOwnNdeath) {
    const auto [leader, renewal] = leading_session();
    ASSERT_FALSE(leader.empty());
    const auto standby = other(leader);

    // Hung, the leader keeps its connections; the standby takes over meanwhile.
    const auto stopped = recorder_->count();
    gateways_[leader]->signal(SIGSTOP);
    ASSERT_TRUE(says(standby, "leader", stopped));
    const auto birth = index_of(node_topic("NBIRTH"), stopped);
    ASSERT_TRUE(birth);
    // Resumed, it finds its lease lapsed and ends its session itself: its NDEATH, late, names
    // its own session, which a host tells from the new one.
    const auto resumed = recorder_->count();
    gateways_[leader]->signal(SIGCONT);
    ASSERT_TRUE(says(leader, "standby", resumed));
    const auto death = index_of(node_topic("NDEATH"), *birth);
    ASSERT_TRUE(death) << "the leader that stood by said no NDEATH";
    const auto all = recorder_->messages();
    EXPECT_EQ(bd_seq_of(all[*death].payload), std::to_string(renewal.value("bd_seq", -1)));
    EXPECT_EQ(bd_seq_of(all[*birth].payload),
              std::to_string((renewal.value("bd_seq", 0) + 1) % 256));
    EXPECT_TRUE(gateways_[leader]->wait_for_output(
        "session with bdSeq " + std::to_string(renewal.value("bd_seq", -1)) + " ended (NDEATH)"));
    // The new session goes on: its devices are born, and it sends their data.
    ASSERT_TRUE(index_of(device_topic("DBIRTH", "plant"), *birth));
    const auto data_from = recorder_->count();
    send_plant(2, 11);
    ASSERT_TRUE(index_of(device_topic("DDATA", "plant"), data_from));
    if (leaderships(stopped) == 1) {
        std::size_t births = 0;
        for (const auto& m : recorder_->messages()) births += m.topic == node_topic("NBIRTH");
        EXPECT_EQ(births, 2u);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
