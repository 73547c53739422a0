// No sample lost across a takeover (docs/redundancy.md): two real gateways on one real
// Mosquitto, both consuming a counter the test sends to each of them every 20 ms, with
// `mqtt.batch`. The leader is killed (SIGKILL) while the counter runs; for a takeover (1 s) no
// one publishes, then the new leader publishes on `_history` what the old one had not had
// acknowledged and goes on live. A subscriber of `_values` and `_history` gets every value, in
// order on each topic, once on each.

#include <signal.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <thread>

#include "eip2mqtt/core/time.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/paced_producer.hpp"
#include "tests/support/pair_fixture.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/tahu.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

const std::string values_topic = "test/line/_values";
const std::string history_topic = "test/line/_history";
const std::string leader_topic = "test/_gateway/_pair/turbine/leader";

/// COUNTER of each message on `topic` from message `from` on, in arrival order; a DUP repeat
/// of a payload already received is the broker's doing, left out.
std::vector<std::uint64_t> counters_on(const std::vector<Received>& all, const std::string& topic,
                                       std::size_t from = 0) {
    std::vector<std::uint64_t> out;
    std::set<std::string> payloads;
    for (auto i = from; i < all.size(); ++i) {
        const auto& m = all[i];
        if (m.topic != topic) continue;
        if (!payloads.insert(m.payload).second && m.duplicate) continue;
        out.push_back(json::parse(m.payload).at("values").at("COUNTER").get<std::uint64_t>());
    }
    return out;
}

bool consecutive(const std::vector<std::uint64_t>& values) {
    for (std::size_t i = 1; i < values.size(); ++i) {
        if (values[i] != values[i - 1] + 1) return false;
    }
    return true;
}

class HotStandbyHistoryTest : public PairTest {
protected:
    void SetUp() override {
        broker_ = std::make_unique<Mosquitto>();
        before_start();
        recorder_ = std::make_unique<MqttRecorder>(
            broker_->url(), std::vector<std::string>{values_topic, history_topic, leader_topic,
                                                     "test/_gateway/+/role",
                                                     "test/_gateway/+/metrics", "spBv1.0/#"});
        const auto exchange = ExchangeYaml::consume("line", "10.0.0.2", 7)
                                  .length(4)
                                  .period_ms(20)
                                  .timeout_ms(0)
                                  .tag("COUNTER", "0.0", "udint")
                                  .str();
        start_units([&](const std::string& id, std::uint16_t port) {
            return unit_config(id, broker_url(id), port, exchange, ", batch: true", sections());
        });
    }
    virtual void before_start() {}
    virtual std::string sections() const { return ""; }
    virtual std::string broker_url(const std::string&) const { return broker_->url(); }
    void TearDown() override {
        producer_.reset();
        PairTest::TearDown();
    }

    /// Datagram `n` of the counter, sent to both units, as a multicast group both join would.
    void start_counter() {
        producer_ = std::make_unique<PacedProducer>(
            [](std::uint64_t n) {
                const auto time = core::wire_time(std::chrono::system_clock::now());
                return DatagramBuilder("10.0.0.2", 7, 4)
                    .request_id(static_cast<std::uint16_t>(n))
                    .timestamp(time.seconds, time.nanoseconds)
                    .set("0.0", core::plan::TagType::udint, std::uint64_t{n})
                    .build();
            },
            [this](const std::vector<std::byte>& datagram) {
                for (const auto& [id, port] : ports_) sender_.send_to(port, datagram);
            },
            20ms);
    }
    /// Waits for `_values` to carry `value` (or more) from message `from` on.
    bool values_reach(std::uint64_t value, std::size_t from = 0) {
        return recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                for (auto i = from; i < all.size(); ++i) {
                    if (all[i].topic != values_topic) continue;
                    const auto j = json::parse(all[i].payload, nullptr, false);
                    if (j.is_object() && j["values"].value("COUNTER", 0u) >= value) return true;
                }
                return false;
            },
            30s);
    }
    /// Waits for a renewal of `leader` whose watermark names the counter's exchange.
    std::optional<Received> renewal_with_watermark(const std::string& leader) {
        return recorder_->wait_for_message(
            leader_topic,
            [&](const std::string& p) {
                const auto j = json::parse(p, nullptr, false);
                return j.is_object() && j.value("id", "") == leader && !j.contains("claim") &&
                       j.contains("watermarks") && j["watermarks"].contains("line");
            },
            10s);
    }

    /// Kills `old` while the counter runs; once `standby` leads and is live again well past the
    /// takeover, the counter stops, and `last`, its last value, arrives with `_history`.
    void kill_while_counting(const std::string& old, const std::string& standby,
                             std::uint64_t& last) {
        const auto killed = recorder_->count();
        gateways_[old]->signal(SIGKILL);
        ASSERT_TRUE(gateways_[old]->wait(10s).has_value());
        gateways_[old].reset();
        ASSERT_TRUE(says(standby, "leader", killed));
        const auto taken_over = recorder_->count();
        ASSERT_TRUE(values_reach(producer_->last() + 25, taken_over));
        last = producer_->pause();
        ASSERT_TRUE(values_reach(last, taken_over));
        ASSERT_TRUE(recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                const auto values = counters_on(all, values_topic);
                return !counters_on(all, history_topic).empty() && !values.empty() &&
                       values.back() == last;
            },
            10s))
            << "nothing on _history";
    }
    /// A leader (`old`) and its standby, the counter running, `_values` past 50 and a renewal
    /// naming the counter's watermark.
    void count_under_a_leader(std::string& old, std::string& standby) {
        old = leader_beside_standby();
        ASSERT_FALSE(old.empty()) << "nobody leads";
        standby = other(old);
        start_counter();
        ASSERT_TRUE(values_reach(50));
        ASSERT_TRUE(renewal_with_watermark(old).has_value());
    }
    /// Every `_history` message says it is history (MQTT 5 user property).
    static void expect_historical(const std::vector<Received>& all) {
        for (const auto& m : all) {
            if (m.topic != history_topic) continue;
            EXPECT_NE(std::find(m.user_properties.begin(), m.user_properties.end(),
                                std::pair<std::string, std::string>{"historical", "true"}),
                      m.user_properties.end());
        }
    }
    /// `replayed` samples counted by the new leader, in metrics that pass their schema.
    void expect_counted(const std::string& standby, std::size_t replayed) {
        const auto metrics = recorder_->wait_for_message(
            "test/_gateway/" + standby + "/metrics",
            [&](const std::string& p) {
                const auto j = json::parse(p, nullptr, false);
                return j.is_object() && j.contains("pair") &&
                       j["pair"].value("samples_replayed", 0u) == replayed;
            },
            10s);
        ASSERT_TRUE(metrics.has_value());
        EXPECT_EQ(schema_problem(schema_file("metrics.json"), metrics->payload), "");
        EXPECT_EQ(json::parse(metrics->payload)["pair"].value("window_overflow", 1), 0);
    }

    UdpClient sender_;
    std::unique_ptr<PacedProducer> producer_;
};

TEST_F(HotStandbyHistoryTest, EveryValueArrivesOnceAcrossAKillOfTheLeader) {
    const auto old = leader_beside_standby();
    ASSERT_FALSE(old.empty()) << "nobody leads";
    const auto standby = other(old);
    start_counter();
    ASSERT_TRUE(values_reach(50));
    const auto renewal = renewal_with_watermark(old);
    ASSERT_TRUE(renewal.has_value());
    EXPECT_EQ(schema_problem(schema_file("leader.json"), renewal->payload), "");

    std::uint64_t last = 0;
    ASSERT_NO_FATAL_FAILURE(kill_while_counting(old, standby, last));
    const auto all = recorder_->messages();
    const auto values = counters_on(all, values_topic);
    const auto history = counters_on(all, history_topic);
    // `_values`: the old leader's run, a gap while no one led, the new leader's run.
    ASSERT_FALSE(values.empty());
    const auto gap =
        std::adjacent_find(values.begin(), values.end(), [](auto a, auto b) { return b != a + 1; });
    ASSERT_NE(gap, values.end()) << "no sample fell between the two leaders";
    const std::vector<std::uint64_t> old_run(values.begin(), gap + 1);
    const std::vector<std::uint64_t> new_run(gap + 1, values.end());
    EXPECT_TRUE(consecutive(old_run));
    EXPECT_TRUE(consecutive(new_run)) << "more than one gap on _values";
    EXPECT_EQ(new_run.back(), last);
    // `_history`: the gap, in order, meeting the new leader's first live value exactly, and
    // starting no later than the old leader's last: every value once on each topic.
    EXPECT_TRUE(consecutive(history));
    EXPECT_LE(history.front(), old_run.back() + 1);
    EXPECT_EQ(history.back() + 1, new_run.front());
    // The old leader's last values that reach `_history` too are those it had acknowledged
    // after its last renewal the standby heard: said on both topics, as a QoS 1 repeat.
    const auto repeated =
        history.front() <= old_run.back() ? old_run.back() - history.front() + 1 : std::uint64_t{0};
    std::cout << "old leader to " << old_run.back() << ", _history " << history.front() << " to "
              << history.back() << " (" << repeated << " repeated), new leader from "
              << new_run.front() << "\n";
    expect_historical(all);
    expect_counted(standby, history.size());
}

/// The pair is a Sparkplug edge node as well.
class SparkplugHistoryTest : public HotStandbyHistoryTest {
protected:
    std::string sections() const override { return "sparkplug: { group_id: plant1 }\n"; }
};

TEST_F(SparkplugHistoryTest, TheTakeoversReplayReachesSparkplugHostsAsHistoricalDdataInOrder) {
    std::string old, standby;
    ASSERT_NO_FATAL_FAILURE(count_under_a_leader(old, standby));
    std::uint64_t last = 0;
    ASSERT_NO_FATAL_FAILURE(kill_while_counting(old, standby, last));
    const auto history = counters_on(recorder_->messages(), history_topic);
    ASSERT_FALSE(history.empty());
    // The new leader's node says the same samples, once it is born: historical DDATA, read by
    // Tahu, in the order of `_history`.
    const std::string ddata = "spBv1.0/plant1/DDATA/turbine/line";
    const auto historical_now = [&] {
        std::vector<std::string> payloads;
        for (const auto& m : recorder_->messages()) {
            if (m.topic == ddata) payloads.push_back(m.payload);
        }
        std::vector<std::uint64_t> values;
        for (const auto& payload : tahu_decode_all(payloads)) {
            for (const auto& metric : payload.at("metrics")) {
                if (metric.value("isHistorical", false)) {
                    values.push_back(std::stoull(metric.at("value").dump()));
                }
            }
        }
        return values;
    };
    // Bounded polling: one run of Node.js a look, not one a message.
    auto historical = historical_now();
    for (int look = 0; look < 40 && historical.size() < history.size(); ++look) {
        std::this_thread::sleep_for(500ms);
        historical = historical_now();
    }
    EXPECT_EQ(historical, history);
}

/// The standby reaches the broker through a proxy the test cuts in one direction: what it
/// sends goes nowhere, what the broker sends it still comes.
class CutOffHistoryTest : public HotStandbyHistoryTest {
protected:
    void before_start() override {
        for (const std::string id : {"gw-a", "gw-b"}) {
            proxies_[id] = std::make_unique<TcpProxy>(broker_->port());
        }
    }
    std::string broker_url(const std::string& id) const override {
        return "tcp://127.0.0.1:" + std::to_string(proxies_.at(id)->port());
    }
    std::map<std::string, std::unique_ptr<TcpProxy>> proxies_;
};

TEST_F(CutOffHistoryTest, AUnitThatLedCutOffNeverReplaysOnceThePathIsBack) {
    std::string old, standby;
    ASSERT_NO_FATAL_FAILURE(count_under_a_leader(old, standby));

    const auto killed = recorder_->count();
    gateways_[old]->signal(SIGKILL);
    ASSERT_TRUE(gateways_[old]->wait(10s).has_value());
    gateways_[old].reset();
    // Its claim reached the broker, which acknowledges it; nothing it sends from now on does.
    ASSERT_TRUE(recorder_->wait_for_message(
        leader_topic,
        [&](const std::string& p) {
            const auto j = json::parse(p, nullptr, false);
            return j.is_object() && j.value("id", "") == standby && j.contains("claim");
        },
        10s, killed));
    proxies_[standby]->stall_upstream();
    // It leads on that claim, cut off, until its lease lapses: its takeover's replay, if it
    // made one, waits in its connection.
    ASSERT_TRUE(gateways_[standby]->wait_for_output("pair: leading, epoch", 10s));
    ASSERT_TRUE(gateways_[standby]->wait_for_output("pair: standing by", 10s));
    const auto back = recorder_->count();
    proxies_[standby]->resume();
    // It takes over again, reaching the broker this time, and replays then.
    ASSERT_TRUE(values_reach(producer_->last() + 25, back));
    const auto last = producer_->pause();
    ASSERT_TRUE(values_reach(last, back));
    ASSERT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) { return !counters_on(all, history_topic).empty(); },
        10s))
        << "nothing on _history";
    const auto history = counters_on(recorder_->messages(), history_topic);
    // One replay: each sample once, in order (the replay of the leadership cut off, delivered
    // once the path was back, would repeat them and go back in time).
    EXPECT_TRUE(consecutive(history)) << ::testing::PrintToString(history);
    expect_historical(recorder_->messages());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
