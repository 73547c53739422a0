// Store and forward through outages with the real binary, a real Mosquitto and real UDP: the
// journal on a really full disk (a 2 MB tmpfs as gateway.state_dir) through two outages and a
// restart, and the Sparkplug node's history over three outages, replayed on the node's own
// connection once it is born again, and through an NDEATH in the middle of its replay.

#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <thread>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/paced_producer.hpp"
#include "tests/support/prometheus_page.hpp"
#include "tests/support/tahu.hpp"
#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

class HistoryOutagesTest : public GatewayTest {
protected:
    GatewayOptions broker_keeping_everything() {
        GatewayOptions options;
        options.broker.persistence = true;  // the recorder's session survives the outages
        options.broker.extra_config = "max_queued_messages 0\n";
        options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(metrics_port_) + "\n";
        return options;
    }

    /// The first value (`field` of `values`) of each delivery on `topic_name`, in arrival
    /// order; a DUP repeat of a payload already received is the broker's doing, left out.
    std::vector<std::uint64_t> values_on(const std::string& topic_name, const std::string& field,
                                         const std::vector<Received>& all) const {
        std::vector<std::uint64_t> out;
        std::set<std::string_view> payloads;
        for (const auto& m : all) {
            if (m.topic != topic_name) continue;
            if (!payloads.insert(m.payload).second && m.duplicate) continue;
            const auto payload = json::parse(m.payload, nullptr, false);
            if (!payload.is_object() || !payload.contains("values") ||
                !payload["values"].contains(field)) {
                ADD_FAILURE() << "no " << field << " in " << m.payload;
                continue;
            }
            out.push_back(payload["values"][field].get<std::uint64_t>());
        }
        return out;
    }

    /// Waits until the last delivery on `topic_name` (a DUP repeat of a payload already received
    /// left out, as values_on does) carries `value` in `field`. Each message is parsed once: the
    /// predicate runs on every arrival, and parsing every `_values` again each time (tens of
    /// thousands of 3 KB documents) starved the recording on a loaded machine.
    bool wait_last_value(const std::string& topic_name, const std::string& field,
                         std::uint64_t value, std::chrono::seconds timeout) {
        std::size_t next = 0;
        std::optional<std::uint64_t> newest;
        std::set<std::size_t> payloads;  // hashes: the recorded strings move as the vector grows
        return recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                for (; next < all.size(); ++next) {
                    const auto& m = all[next];
                    if (m.topic != topic_name) continue;
                    const auto seen = !payloads.insert(std::hash<std::string>{}(m.payload)).second;
                    if (seen && m.duplicate) continue;
                    const auto payload = json::parse(m.payload, nullptr, false);
                    if (payload.is_object() && payload.contains("values") &&
                        payload["values"].contains(field)) {
                        newest = payload["values"][field].get<std::uint64_t>();
                    }
                }
                return newest == value;
            },
            timeout);
    }
    void stop_broker() {
        broker_->stop();
        ASSERT_TRUE(wait_output(" lost: ")) << gateway_->output();
    }
    void start_broker() {
        const auto from = recorder_->count();
        broker_->start();
        wait_online(from);
    }
    /// Bounded polling of the gateway's log for the `count`th `text`.
    bool wait_output(const std::string& text) {
        const auto count = ++expected_[text];
        const auto deadline = std::chrono::steady_clock::now() + 15s;
        while (std::chrono::steady_clock::now() < deadline) {
            const auto output = gateway_->output();
            std::size_t seen = 0;
            for (auto at = output.find(text); at != std::string::npos;
                 at = output.find(text, at + 1)) {
                ++seen;
            }
            if (seen >= count) return true;
            std::this_thread::sleep_for(20ms);
        }
        return false;
    }
    /// Pauses the producer once the gateway took every datagram sent: one still in the
    /// socket's buffer at a stop would be neither live nor journaled, and look like an entry
    /// the journal lost.
    void pause_once_taken() {
        const auto sent = producer_->pause();
        ASSERT_TRUE(
            wait_prometheus_figure(metrics_port_, "eip2mqtt_datagrams_accepted_total",
                                   [&](double v) { return v >= static_cast<double>(sent); }))
            << http_get(metrics_port_, "/metrics");
    }
    /// Waits for a metrics message saying the journal is empty and no replay runs.
    bool wait_replayed(std::chrono::seconds timeout) {
        const auto from = recorder_->count();
        return recorder_
            ->wait_for_message(
                metrics_topic(),
                [](const std::string& p) {
                    const auto m = json::parse(p, nullptr, false);
                    return m.is_object() && m.contains("history") &&
                           m["history"].value("entries", -1) == 0 &&
                           m["history"].value("replaying", true) == false;
                },
                timeout, from)
            .has_value();
    }

    /// Live values (T0 / 1000) show `outages` gaps. In each, the journal kept the newest
    /// entries: what reached `history` runs without a hole up to the gap's last value, in
    /// order, and only the oldest of the gap, those the full disk could not hold, are missing.
    void expect_newest_kept_in_each_outage(const std::string& values, const std::string& history,
                                           std::size_t outages) {
        const auto all = recorder_->messages();
        std::set<std::uint64_t> live;
        for (const auto v : values_on(values, "T0", all)) live.insert(v / 1000);
        std::vector<std::uint64_t> replayed;
        for (const auto v : values_on(history, "T0", all)) replayed.push_back(v / 1000);
        const std::set<std::uint64_t> replayed_set(replayed.begin(), replayed.end());
        EXPECT_LE(replayed.size() - replayed_set.size(), 10u) << "QoS 1 repeats at most";
        std::vector<std::pair<std::uint64_t, std::uint64_t>> gaps;  // first and last value
        for (auto it = live.begin(); it != live.end() && std::next(it) != live.end(); ++it) {
            if (*std::next(it) > *it + 1) gaps.emplace_back(*it + 1, *std::next(it) - 1);
        }
        ASSERT_EQ(gaps.size(), outages) << "live values should show the outages";
        for (const auto& [first, end] : gaps) {
            std::uint64_t kept = 0;
            for (auto v = end; v >= first && replayed_set.contains(v); --v) ++kept;
            std::uint64_t stray = 0;
            for (auto v = first; v + kept <= end; ++v) stray += replayed_set.contains(v) ? 1 : 0;
            EXPECT_GT(kept, 300u) << "outage " << first << "-" << end;
            EXPECT_EQ(stray, 0u) << "outage " << first << "-" << end
                                 << ": an older entry outlived a newer";
            EXPECT_LT(kept, end - first + 1) << "the disk never filled";
            std::cout << "outage of values " << first << "-" << end << ": " << kept
                      << " newest replayed, " << end - first + 1 - kept << " oldest dropped\n";
        }
        std::vector<std::uint64_t> firsts;
        std::set<std::uint64_t> seen;
        for (const auto v : replayed) {
            if (seen.insert(v).second) firsts.push_back(v);
        }
        EXPECT_TRUE(std::is_sorted(firsts.begin(), firsts.end()));
    }

    std::map<std::string, std::size_t> expected_;
    std::uint16_t metrics_port_ = free_tcp_port();
    std::unique_ptr<Tmpfs> disk_;
    std::unique_ptr<PacedProducer> producer_;
};

TEST_F(HistoryOutagesTest, AFullDiskKeepsTheNewestThroughTwoOutagesAndARestart) {
    disk_ = std::make_unique<Tmpfs>(2 << 20, false, dir_.path() + "/state");
    if (!disk_->mounted()) GTEST_SKIP() << disk_->error();
    // 200 tags, every one changing in every datagram, 200 datagrams a second: about 200 KB a
    // second to journal, so the 2 MB disk is full long before a 20 s outage ends.
    constexpr int tags = 200;
    auto wide = ExchangeYaml::consume("wide", "10.0.0.3", 8);
    wide.length(tags * 4).timeout_ms(0);
    for (int i = 0; i < tags; ++i)
        wide.tag("T" + std::to_string(i), std::to_string(i * 4) + ".0", "udint");
    start(wide.str(),
          "  batch: true\n  batch_first: true\n  store_and_forward:\n    enabled: true\n"
          "    replay_rate: 2000\n",
          broker_keeping_everything());
    const auto values = topic("wide/_values");
    const auto history = topic("wide/_history");
    // 40,000 tag publications a second are not this test's subject: the recorder takes only
    // what it reads, or it would fall minutes behind.
    recorder_ = std::make_unique<MqttRecorder>(
        broker_->url(),
        std::vector<std::string>{values, history, metrics_topic(), availability_topic()});
    producer_ = std::make_unique<PacedProducer>(
        [](std::uint64_t n) {
            DatagramBuilder datagram("10.0.0.3", 8, tags * 4);
            datagram.request_id(static_cast<std::uint16_t>(n));
            for (std::uint16_t i = 0; i < tags; ++i) {
                datagram.set(std::to_string(i * 4) + ".0", TagType::udint,
                             std::uint64_t{n * 1000 + i});
            }
            return datagram.build();
        },
        [this](const auto& d) { send(d); }, 5ms);
    ASSERT_TRUE(recorder_->wait_for_message(values, nullptr, 10s));

    stop_broker();
    std::this_thread::sleep_for(20s);  // the scenario: the first outage
    start_broker();
    EXPECT_TRUE(wait_replayed(60s)) << gateway_->output();

    stop_broker();
    std::this_thread::sleep_for(10s);  // the scenario: the second outage
    // A restart in the middle of it, on the full disk; nothing is sent while it is down.
    ASSERT_NO_FATAL_FAILURE(pause_once_taken());
    gateway_->signal(SIGTERM);
    ASSERT_TRUE(gateway_->wait(10s).has_value());
    options_.wait_online = false;
    start_gateway();
    expected_.clear();
    ASSERT_TRUE(wait_output("listening on UDP")) << gateway_->output();
    producer_->resume();
    std::this_thread::sleep_for(3s);  // the scenario: the outage goes on after the restart
    start_broker();
    EXPECT_TRUE(wait_replayed(60s)) << gateway_->output();
    const auto last = producer_->pause();
    ASSERT_TRUE(wait_last_value(values, "T0", last * 1000, 30s));

    expect_newest_kept_in_each_outage(values, history, 2);
    EXPECT_EQ(gateway_->output().find("journal failed"), std::string::npos) << gateway_->output();
    EXPECT_EQ(gateway_->output().find("set aside"), std::string::npos) << gateway_->output();
}

/// One consumed exchange (`line`, a counter) at 100 datagrams a second, Sparkplug behind a
/// primary host, store and forward replaying at `replay_rate`.
class HistoryOutagesSparkplugTest : public HistoryOutagesTest {
protected:
    void start_line(int replay_rate) {
        auto options = broker_keeping_everything();
        options.sections += "sparkplug:\n  group_id: plant\n  primary_host_id: scada\n";
        start(ExchangeYaml::consume("line", "10.0.0.2", 7)
                  .length(4)
                  .period_ms(10)
                  .timeout_ms(0)
                  .tag("COUNTER", "0.0", "udint")
                  .str(),
              "  batch: true\n  store_and_forward:\n    enabled: true\n    replay_rate: " +
                  std::to_string(replay_rate) + "\n",
              std::move(options));
        host(true);
        producer_ = std::make_unique<PacedProducer>(
            [](std::uint64_t n) {
                return DatagramBuilder("10.0.0.2", 7, 4)
                    .request_id(static_cast<std::uint16_t>(n))
                    .set("0.0", TagType::udint, std::uint64_t{n})
                    .build();
            },
            [this](const auto& d) { send(d); }, 10ms);
        ASSERT_TRUE(recorder_->wait_for_message(ddata_, nullptr, 10s));
    }
    /// The primary host's STATE, retained: after an outage, the node waits for it again.
    void host(bool online) {
        recorder_->publish(state_,
                           std::string(R"({"online":)") + (online ? "true" : "false") +
                               R"(,"timestamp":)" + std::to_string(++host_timestamp_) + "}",
                           true);
    }
    /// The host offline, a 5 s outage, the broker back: waits for the JSON tree's replay of
    /// the outage, made while the node is not born.
    void outage_with_the_host_offline() {
        host(false);
        stop_broker();
        std::this_thread::sleep_for(5s);  // the scenario: outages of 5 s
        const auto from = recorder_->count();
        start_broker();
        ASSERT_TRUE(recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                return count_after(all, history_, from) >= 300;
            },
            30s))
            << gateway_->output();
    }
    static std::size_t count_after(const std::vector<Received>& all, const std::string& topic_name,
                                   std::size_t from) {
        return static_cast<std::size_t>(
            std::count_if(all.begin() + static_cast<std::ptrdiff_t>(from), all.end(),
                          [&](const Received& m) { return m.topic == topic_name; }));
    }
    /// Read by Tahu: the node's historical samples, each a journaled one (what `_history`
    /// got), none missing.
    void expect_every_journaled_sample_as_sparkplug_history(std::size_t at_least) {
        const auto all = recorder_->messages();
        const auto json_history = values_on(history_, "COUNTER", all);
        const std::set<std::uint64_t> journaled(json_history.begin(), json_history.end());
        ASSERT_GT(journaled.size(), at_least);
        std::vector<std::string> payloads;
        for (const auto& m : all) {
            if (m.topic == ddata_) payloads.push_back(m.payload);
        }
        std::vector<std::uint64_t> historical;
        for (const auto& payload : tahu_decode_all(payloads)) {
            for (const auto& metric : payload.at("metrics")) {
                if (metric.value("isHistorical", false)) {
                    historical.push_back(metric.at("value").get<std::uint64_t>());
                }
            }
        }
        const std::set<std::uint64_t> historical_set(historical.begin(), historical.end());
        std::vector<std::uint64_t> missing;
        std::set_difference(journaled.begin(), journaled.end(), historical_set.begin(),
                            historical_set.end(), std::back_inserter(missing));
        EXPECT_TRUE(missing.empty()) << missing.size() << " of " << journaled.size()
                                     << " journaled samples never came as Sparkplug history, "
                                     << "first " << (missing.empty() ? 0 : missing.front());
        for (const auto v : historical_set) EXPECT_TRUE(journaled.contains(v)) << v;
        EXPECT_LE(historical.size() - historical_set.size(), 15u) << "repeats of a lost connection";
        std::cout << journaled.size() << " journaled samples, " << historical_set.size()
                  << " as Sparkplug history (" << historical.size() << " deliveries)\n";
    }

    const std::string state_ = "spBv1.0/STATE/scada";
    const std::string ddata_ = "spBv1.0/plant/DDATA/test-gw/line";
    const std::string history_ = topic("line/_history");
    int host_timestamp_ = 0;
};

TEST_F(HistoryOutagesSparkplugTest, ThreeOutagesHaveEveryJournaledSample) {
    // The node's births wait for its primary host, which says it is online again only once the
    // JSON tree has replayed the outage: the node's own replay must wait for its births, and the
    // journal keep each entry until the node has it too.
    start_line(500);
    for (int outage = 0; outage < 3; ++outage) {
        outage_with_the_host_offline();
        host(true);
        EXPECT_TRUE(wait_replayed(60s)) << gateway_->output();
    }
    producer_->pause();
    expect_every_journaled_sample_as_sparkplug_history(1000);  // 15 s at 100 a second
}

TEST_F(HistoryOutagesSparkplugTest, AnNdeathInTheMiddleOfTheReplayLosesNothing) {
    // The host goes offline in the middle of the replay: the node says its NDEATH, leaves the
    // broker and connects again (the broker says the NDEATH too, as the will its DISCONNECT
    // asks for). What the replay had not had acknowledged goes again after the next births, and
    // the journal empties.
    start_line(200);
    outage_with_the_host_offline();
    producer_->pause();  // from here, every DDATA is history: 5 s of it, 2.5 s of replay
    const auto from = recorder_->count();
    host(true);
    ASSERT_TRUE(recorder_->wait_for(
        [&](const std::vector<Received>& all) { return count_after(all, ddata_, from) >= 100; },
        30s));
    const auto death_at = recorder_->count();
    host(false);
    const std::string death = "spBv1.0/plant/NDEATH/test-gw";
    ASSERT_TRUE(recorder_->wait_for_message(death, nullptr, 10s, death_at)) << gateway_->output();
    host(true);
    EXPECT_TRUE(wait_replayed(60s)) << gateway_->output();
    // The flap came in the middle of the replay, the births after the NDEATH.
    const auto all = recorder_->messages();
    EXPECT_GT(count_after(all, ddata_, death_at), 0u);
    std::vector<std::string> node_messages;
    for (auto i = death_at; i < all.size(); ++i) {
        if (all[i].topic.find("/NDEATH/") != std::string::npos ||
            all[i].topic.find("/NBIRTH/") != std::string::npos) {
            node_messages.push_back(all[i].topic);
        }
    }
    // The NDEATH once or twice (the node's, then the broker's), then the next NBIRTH.
    ASSERT_GE(node_messages.size(), 2u);
    EXPECT_EQ(node_messages.back(), "spBv1.0/plant/NBIRTH/test-gw");
    node_messages.pop_back();
    EXPECT_LE(node_messages.size(), 2u);
    for (const auto& topic_name : node_messages) EXPECT_EQ(topic_name, death);
    expect_every_journaled_sample_as_sparkplug_history(300);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
