// Several brokers at once with the real binary, two real Mosquittos and real UDP: the test's own
// broker (connection `site`) and a second one (`enterprise`: its own base topic, payload
// profile, buffer and journal). The enterprise broker stopped for a minute: the site's
// subscriber gets every sample live all along, and the enterprise's gets the minute replayed on
// its return. A write is taken and answered on the connection it came through.

#include <algorithm>
#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/store_and_forward_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using nlohmann::json;
using namespace std::chrono_literals;

constexpr const char* kJournal = "    enabled: true\n    replay_rate: 500\n";
constexpr const char* kEnterpriseBase = "ent";

/// The second broker and a recorder of everything on it, whose session outlives the broker's
/// stop (persistence), so that what the gateway replays before the recorder is back waits for it.
struct SecondBroker {
    SecondBroker() : broker(keeping_everything()), recorder(broker.url(), {"#"}, "ent-recorder") {}

    static MosquittoOptions keeping_everything() {
        MosquittoOptions options;
        options.persistence = true;
        options.extra_config = "max_queued_messages 0\n";
        return options;
    }
    std::string online_topic() const {
        return std::string(kEnterpriseBase) + "/_gateway/test-gw/state";
    }

    Mosquitto broker;
    MqttRecorder recorder;
};

/// The enterprise connection as a list item: its own base topic, `value` payloads, a journal.
std::string enterprise_connection(const std::string& url, const std::string& more = "") {
    return "  - name: enterprise\n    url: " + url + "\n    base_topic: " + kEnterpriseBase +
           "\n    qos: 1\n    batch: true\n    payload: value\n    metrics_interval_s: 1\n" +
           "    store_and_forward:\n      enabled: true\n      replay_rate: 500\n" + more;
}

class SeveralBrokersTest : public StoreAndForwardTest {
protected:
    void start_both() {
        GatewayOptions options;
        options.broker = SecondBroker::keeping_everything();
        options.more_connections = enterprise_connection(second_.broker.url());
        start_gateway_with(kJournal, std::move(options), "", [this] {
            ASSERT_TRUE(second_.recorder.wait_for_message(
                second_.online_topic(), [](const std::string& p) { return p == "online"; }, 30s));
        });
    }

    /// Waits until the COUNTER values `recorder` received on `topics` satisfy `done`. Each
    /// message is parsed once: the predicate runs on every arrival, and parsing thousands of
    /// `_values` again each time starves the recording.
    static bool wait_values(MqttRecorder& recorder, const std::set<std::string>& topics,
                            const std::function<bool(const std::set<std::uint64_t>&)>& done,
                            std::chrono::seconds timeout) {
        std::size_t next = 0;
        std::set<std::uint64_t> seen;
        return recorder.wait_for(
            [&](const std::vector<Received>& all) {
                for (; next < all.size(); ++next) {
                    if (topics.contains(all[next].topic)) seen.insert(counter_of(all[next]));
                }
                return done(seen);
            },
            timeout);
    }

    SecondBroker second_;
};

TEST_F(SeveralBrokersTest, OneBrokerDownForAMinuteHoldsUpNothingAndGetsItsReplay) {
    start_both();
    ASSERT_TRUE(recorder_->wait_for_message(topic("line/_values"), nullptr, 10s));
    ASSERT_TRUE(second_.recorder.wait_for_message("ent/line/_values", nullptr, 10s));
    // Each connection speaks its own profile: a bare number on the enterprise's tag topic.
    const auto tag = second_.recorder.wait_for_message("ent/line/COUNTER", nullptr, 10s);
    ASSERT_TRUE(tag.has_value());
    EXPECT_FALSE(json::parse(tag->payload).is_object()) << tag->payload;

    const auto losses = count_output("MQTT [enterprise] connection to");
    second_.broker.stop();
    ASSERT_TRUE(wait_output_count("MQTT [enterprise] connection to", losses + 1))
        << gateway_->output();
    // The outage: a minute of the counter (100 a second), every one of them live on the site.
    const auto at_stop = counter_->last();
    ASSERT_TRUE(wait_values(
        *recorder_, {topic("line/_values")},
        [&](const auto& seen) { return !seen.empty() && *seen.rbegin() >= at_stop + 6000; }, 120s))
        << "stopped at " << at_stop << ", counter at " << counter_->last() << "\n"
        << gateway_->output();

    const auto from = second_.recorder.count();
    second_.broker.start();
    ASSERT_TRUE(second_.recorder.wait_for_message(
        second_.online_topic(), [](const std::string& p) { return p == "online"; }, 60s, from));
    const auto last = pause_when_delivered();
    // The site: every value once, live, nothing replayed (it never lost its broker).
    expect_each_value_once(last, 0);
    EXPECT_TRUE(recorder_->messages_on(topic("line/_history")).empty());
    // Told, not asserted (a duration is the machine's): the longest wait between two of the
    // site's live values while the enterprise broker was down.
    const auto live = recorder_->messages_on(topic("line/_values"));
    std::chrono::steady_clock::duration longest{};
    for (std::size_t i = 1; i < live.size(); ++i)
        longest = std::max(longest, live[i].at - live[i - 1].at);
    RecordProperty(
        "site_longest_gap_ms",
        static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(longest).count()));
    // The enterprise: every value once, the minute through its own journal.
    ASSERT_TRUE(wait_values(
        second_.recorder, {"ent/line/_values", "ent/line/_history"},
        [&](const auto& seen) { return seen.size() >= last; }, 120s))
        << gateway_->output();
    expect_each_value_once(second_.recorder, kEnterpriseBase, last);
    EXPECT_GE(second_.recorder.messages_on("ent/line/_history").size(), 6000u);
}

class SeveralBrokersWriteTest : public GatewayTest {};

TEST_F(SeveralBrokersWriteTest, AWriteIsAnsweredOnTheConnectionItCameThrough) {
    SecondBroker second;
    UdpClient capture;
    GatewayOptions options;
    options.more_connections = enterprise_connection(second.broker.url(), "    writes: true\n");
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture.port()))
              .period_ms(20)
              .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
              .str(),
          "", std::move(options));
    ASSERT_TRUE(second.recorder.wait_for_message(
        second.online_topic(), [](const std::string& p) { return p == "online"; }, 30s));

    const auto from = second.recorder.count();
    second.recorder.publish("ent/sp/SPEED_SP/set", "1234");
    const auto answer =
        second.recorder.wait_for_message("ent/sp/SPEED_SP/set/result", nullptr, 10s, from);
    ASSERT_TRUE(answer.has_value()) << gateway_->output();
    EXPECT_EQ(json::parse(answer->payload)["ok"], true) << answer->payload;
    // Then one through the site: its answer is the only one the site ever sees.
    EXPECT_EQ(json::parse(write_result("sp/SPEED_SP/set", R"({"value":2000})"))["ok"], true);
    EXPECT_EQ(recorder_->messages_on(topic("sp/SPEED_SP/set/result")).size(), 1u);
    EXPECT_EQ(second.recorder.messages_on("ent/sp/SPEED_SP/set/result").size(), 1u);
    // Both trees carry the value written last, each in its own profile, and the enterprise's
    // `_meta` names the tag's topic there.
    const auto meta = second.recorder.wait_for_message("ent/sp/_meta", nullptr, 10s);
    ASSERT_TRUE(meta.has_value());
    EXPECT_EQ(json::parse(meta->payload)["tags"]["SPEED_SP"]["topic"], "ent/sp/SPEED_SP");
    // Its metrics topic tells of its own connection.
    const auto metrics =
        second.recorder.wait_for_message("ent/_gateway/test-gw/metrics", nullptr, 10s);
    ASSERT_TRUE(metrics.has_value());
    EXPECT_EQ(json::parse(metrics->payload)["broker"], second.broker.url());
    EXPECT_TRUE(second.recorder.wait_for_message(
        "ent/sp/SPEED_SP", [](const std::string& p) { return p == "2000.0"; }, 10s))
        << [&] {
               std::string seen;
               for (const auto& m : second.recorder.messages())
                   seen += m.topic + " " + m.payload + "\n";
               return seen;
           }();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
