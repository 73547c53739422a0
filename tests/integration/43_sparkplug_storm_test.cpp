// Sparkplug hosts that misbehave, against the real binary and a real Mosquitto: a flood of
// `Node Control/Rebirth` must not hold up the datagrams (no exchange goes stale, none is
// missed, and the rebirths are coalesced), and a primary host whose STATE flaps must see each
// NDEATH before the next NBIRTH, as a host subscribed at QoS 1 over MQTT 3.1.1 receives them
// (mosquitto_sub), read by Eclipse Tahu's decoder.

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/tahu.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr std::uint32_t exchanges = 20;
constexpr std::size_t tags = 200;
constexpr auto period = 100ms;

std::string node_topic(const std::string& type) { return "spBv1.0/plant1/" + type + "/test-gw"; }

std::string storm_exchanges() {
    std::string yaml;
    for (std::uint32_t e = 1; e <= exchanges; ++e) {
        // A timeout of ten periods: a test machine that is merely busy does not reach it.
        auto exchange = ExchangeYaml::consume("ex" + std::to_string(e), "10.9.9.9", e)
                            .length(2 * tags)
                            .period_ms(100)
                            .timeout_ms(1000);
        for (std::size_t t = 0; t < tags; ++t) {
            exchange.tag("TAG_" + std::to_string(t), std::to_string(2 * t) + ".0", "int",
                         "unit: kPa");
        }
        yaml += exchange.str();
    }
    return yaml;
}

/// Every exchange's datagram each period, their request ids one apart, until stopped: a
/// producer, not a synchronisation.
class Producer {
public:
    explicit Producer(std::function<void(const std::vector<std::byte>&)> send)
        : send_(std::move(send)), thread_([this] { run(); }) {}
    ~Producer() { stop(); }
    void stop() {
        stop_ = true;
        if (thread_.joinable()) thread_.join();
    }
    std::uint16_t rounds() const { return rounds_; }

private:
    void run() {
        auto next = std::chrono::steady_clock::now();
        while (!stop_) {
            ++rounds_;
            for (std::uint32_t e = 1; e <= exchanges; ++e) {
                DatagramBuilder datagram("10.9.9.9", e, 2 * tags);
                datagram.request_id(rounds_).set("0.0", TagType::int_, Value{std::int64_t{1}});
                send_(datagram.build());
            }
            next += period;
            std::this_thread::sleep_until(next);
        }
    }
    std::function<void(const std::vector<std::byte>&)> send_;
    std::atomic<bool> stop_{false};
    std::atomic<std::uint16_t> rounds_{0};
    std::thread thread_;
};

class SparkplugStormTest : public GatewayTest {
protected:
    bool took_every_state(const ChildProcess& host);
};

/// How many lines of `output` contain `text`.
std::size_t lines_with(const std::string& output, const std::string& text) {
    std::size_t count = 0;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        count += line.find(text) != std::string::npos;
    return count;
}

/// At most the first line and one summary a minute (a part started counts) since `since`.
std::size_t throttled_lines_at_most(std::chrono::steady_clock::time_point since) {
    return 2 + static_cast<std::size_t>((std::chrono::steady_clock::now() - since) / 60s);
}

/// An NCMD asking for a rebirth, as a host sends it.
std::string rebirth_request() {
    return tahu_encode({{"timestamp", 1700000000000},
                        {"metrics", json::array({{{"name", "Node Control/Rebirth"},
                                                  {"type", "Boolean"},
                                                  {"value", true}}})}});
}

/// Every exchange reports a request id of at least `after` on its `_status` within 60 s.
template <class Topic>
void expect_every_exchange_reports_from(MqttRecorder& recorder, int after, const Topic& topic) {
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    for (std::uint32_t e = 1; e <= exchanges; ++e) {
        const auto status = topic("ex" + std::to_string(e) + "/_status");
        EXPECT_TRUE(recorder
                        .wait_for_message(
                            status,
                            [&](const std::string& payload) {
                                const auto s = json::parse(payload, nullptr, false);
                                return s.is_object() && s.contains("request_id") &&
                                       s["request_id"].is_number_integer() &&
                                       s["request_id"].get<int>() >= after;
                            },
                            std::chrono::duration_cast<std::chrono::milliseconds>(
                                deadline - std::chrono::steady_clock::now()))
                        .has_value())
            << status;
    }
}

/// No exchange's `_status` in `messages` went stale or counts a timeout or a missed datagram.
void expect_no_status_stale_or_missed(const std::vector<Received>& messages) {
    for (const auto& m : messages) {
        if (!m.topic.ends_with("/_status")) continue;
        const auto s = json::parse(m.payload, nullptr, false);
        ASSERT_TRUE(s.is_object()) << m.payload;
        EXPECT_NE(s.value("state", ""), "stale") << m.topic;
        EXPECT_EQ(s.value("timeouts", -1), 0) << m.topic << " " << m.payload;
        EXPECT_EQ(s.value("missed", -1), 0) << m.topic << " " << m.payload;
    }
}

TEST_F(SparkplugStormTest, AFloodOfRebirthRequestsNeitherStalesNorMissesADatagram) {
    GatewayOptions options;
    options.sections = "sparkplug:\n  group_id: plant1\n";
    start(storm_exchanges(), "", options);
    Producer producer([this](const std::vector<std::byte>& d) { send(d); });
    for (std::uint32_t e = 1; e <= exchanges; ++e) {
        expect_field(topic("ex" + std::to_string(e) + "/_status"), "state", "\"ok\"");
    }
    const auto rebirth = rebirth_request();
    // 1,000 requests over 5 s or more (each waits for the broker's PUBACK), some 30 bytes each
    // asking for ~90 kB of births.
    constexpr int requests = 1000;
    const auto storm_start = std::chrono::steady_clock::now();
    for (int i = 0; i < requests; ++i) {
        recorder_->publish(node_topic("NCMD"), rebirth);
        std::this_thread::sleep_until(storm_start + i * 5ms);
    }
    const auto storm = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::steady_clock::now() - storm_start);
    // Every exchange reports at least two seconds of datagrams after the storm.
    const auto after = producer.rounds() + 20;
    expect_every_exchange_reports_from(*recorder_, after,
                                       [this](const std::string& suffix) { return topic(suffix); });
    producer.stop();
    // No exchange went stale, none missed a datagram: nothing waited unread.
    expect_no_status_stale_or_missed(recorder_->messages());
    for (const auto& m : recorder_->messages()) {
        EXPECT_EQ(m.topic.find("/DDEATH/"), std::string::npos) << m.topic;
    }
    // The first request answered at once, the rest by one rebirth a second, not one a request.
    const auto nbirths = recorder_->messages_on(node_topic("NBIRTH")).size();
    std::cout << requests << " rebirth requests in " << storm.count() << " ms: " << nbirths
              << " NBIRTHs, the connection's included\n";
    // The connection's and the first request's at least; coalesced, far fewer than the
    // requests however slow the machine (a rebirth a second of the gateway's own time: the
    // figure against the storm's length is printed above, not asserted).
    EXPECT_GE(nbirths, 2u);
    EXPECT_LT(nbirths, static_cast<std::size_t>(requests / 10));
    // The log says so in a line and a summary a minute, not a line a request.
    EXPECT_LE(lines_with(gateway_->output(), "rebirth requested by NCMD") +
                  lines_with(gateway_->output(), "more rebirth requests by NCMD"),
              throttled_lines_at_most(storm_start))
        << gateway_->output();
    // And the gateway took every request.
    EXPECT_TRUE(recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& payload) {
            const auto m = json::parse(payload, nullptr, false);
            return m.is_object() && m.contains("sparkplug") &&
                   m["sparkplug"].value("rebirth_requests", 0) == requests;
        },
        30s));
}

/// What a host subscribed at QoS 1 over MQTT 3.1.1 received, in order: (topic, payload).
std::vector<std::pair<std::string, std::string>> host_messages(const std::string& output) {
    std::vector<std::pair<std::string, std::string>> messages;
    std::istringstream lines(output);
    std::string line;
    while (std::getline(lines, line)) {
        const auto space = line.find(' ');
        if (!line.starts_with("spBv1.0/") || space == std::string::npos) continue;
        std::string bytes;
        for (std::size_t i = space + 1; i + 1 < line.size(); i += 2) {
            bytes.push_back(static_cast<char>(std::stoi(line.substr(i, 2), nullptr, 16)));
        }
        messages.emplace_back(line.substr(0, space), std::move(bytes));
    }
    return messages;
}

/// `flaps` + 1 STATE payloads, one a line, online and offline in turn from online.
std::string state_lines(int flaps) {
    std::string lines;
    for (int i = 0; i <= flaps; ++i) {
        lines += std::string(R"({"online":)") + (i % 2 == 0 ? "true" : "false") +
                 R"(,"timestamp":)" + std::to_string(2 + i) + "}\n";
    }
    return lines;
}

/// What the node said, of what the host `received`: not the test's own rebirth request, nor
/// the end marker and what came after it.
std::vector<std::pair<std::string, std::string>> node_messages(
    std::vector<std::pair<std::string, std::string>> received) {
    std::erase_if(received, [](const auto& m) { return m.first == node_topic("NCMD"); });
    const auto end = std::find_if(received.begin(), received.end(),
                                  [](const auto& m) { return m.first == "spBv1.0/plant1/end"; });
    received.erase(end, received.end());
    return received;
}

/// What check_births_and_deaths() found.
struct BirthsAndDeaths {
    std::vector<std::string> problems;
    bool born = false;  ///< the last of them was an NBIRTH
};

/// Births and deaths alternate, each death with the bdSeq of the birth before it (a death may
/// come twice: the node says it, then the broker, as the will its DISCONNECT with reason 0x04
/// asks for), and seq counts on from each NBIRTH; `decoded`: the payloads of `received` as Tahu
/// decodes them.
BirthsAndDeaths check_births_and_deaths(
    const std::vector<std::pair<std::string, std::string>>& received,
    const std::vector<json>& decoded) {
    std::vector<std::string> problems;
    bool born = false;
    std::string bd_seq;
    int seq = 0;
    for (std::size_t i = 0; i < received.size(); ++i) {
        const auto& topic = received[i].first;
        const auto& payload = decoded[i];
        const auto problem = [&](const std::string& what) {
            problems.push_back(std::to_string(i) + ": " + topic + ": " + what);
        };
        if (!payload.contains("metrics") || !payload["metrics"].is_array()) {
            problem("no metrics");
            continue;
        }
        const bool birth = topic == node_topic("NBIRTH");
        if (birth || topic == node_topic("NDEATH")) {
            if (birth && born) problem("a second NBIRTH without an NDEATH");
            born = birth;
            const auto value = payload["metrics"].empty()
                                   ? std::string("none")
                                   : payload["metrics"][0].value("value", json()).dump();
            if (birth) bd_seq = value;
            if (value != bd_seq) problem("bdSeq " + value + " after a birth with " + bd_seq);
            if (birth) seq = 0;
            if (!birth) continue;
        }
        const auto expected = std::to_string(seq++);
        if (!born) problem("after the NDEATH");
        if (payload.value("seq", json()) != expected) {
            problem("seq " + payload.value("seq", json()).dump() + ", not " + expected);
        }
    }
    return {problems, born};
}

/// The flaps are over for the node once it is born again on a connection made after the last
/// STATE (retained: online), which `host` sees as an NBIRTH after the first NDEATH: an offline
/// STATE made it leave its connection, and while it connects again it hears none of the rest.
/// Then it reads an NCMD sent after them (one it logs and ignores: a rebirth would add births
/// of its own).
bool SparkplugStormTest::took_every_state(const ChildProcess& host) {
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    const auto births = [&] {
        const auto received = host_messages(host.output());
        return std::count_if(received.begin(), received.end(),
                             [](const auto& m) { return m.first == node_topic("NBIRTH"); });
    };
    while (births() < 2) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(100ms);  // bounded polling of the host's output
    }
    recorder_->publish(node_topic("NCMD"), std::string("\xff\xff\xff", 3));
    return gateway_->wait_for_output("Sparkplug NCMD ignored", 30s);
}

TEST_F(SparkplugStormTest, AFlappingPrimaryHostSeesEachNdeathBeforeTheNextNbirth) {
    UdpClient capture;
    GatewayOptions options;
    options.sections = "sparkplug:\n  group_id: plant1\n  primary_host_id: scada\n";
    start(ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture.port()))
              .period_ms(100)
              .tag("SPEED_SP", "0.0", "real", "writable: true")
              .str(),
          "", options);
    // The host: MQTT 3.1.1 at QoS 1, so the broker holds at most 20 of its QoS 1 messages in
    // flight and queues the rest, where a QoS 0 one could pass them.
    // Its lines as they come (stdbuf): the test reads them while it runs.
    ChildProcess host({"/usr/bin/stdbuf", "-oL", "/usr/bin/mosquitto_sub", "-d", "-h", "127.0.0.1",
                       "-p", std::to_string(broker_->port()), "-q", "1", "-t", "spBv1.0/plant1/#",
                       "-F", "%t %x"});
    ASSERT_TRUE(host.wait_for_output("SUBACK", 20s)) << host.output();
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":1})", true);
    ASSERT_TRUE(recorder_->wait_for_message(node_topic("NBIRTH"), nullptr, 20s).has_value());

    // 4,000 changes of its STATE as fast as the broker takes them, ending online.
    const auto flaps_start = std::chrono::steady_clock::now();
    constexpr int flaps = 4000;
    const auto file = dir_.write("flaps.txt", state_lines(flaps));
    const auto pub = run_command(
        {"/bin/sh", "-c",
         "exec /usr/bin/mosquitto_pub -h 127.0.0.1 -p " + std::to_string(broker_->port()) +
             " -t spBv1.0/STATE/scada -q 1 -r -l < " + file},
        120s);
    ASSERT_EQ(pub.status, 0) << pub.output;
    ASSERT_TRUE(took_every_state(host)) << gateway_->output() << host.output();
    // A clean stop ends with an NDEATH. A QoS 1 message after it reaches the host after
    // everything the node said (QoS 0 messages are never queued behind QoS 1 ones).
    gateway_->signal(SIGTERM);
    ASSERT_EQ(gateway_->wait(20s), 0);
    recorder_->publish("spBv1.0/plant1/end", "end");
    ASSERT_TRUE(host.wait_for_output("spBv1.0/plant1/end", 60s));
    const auto received = node_messages(host_messages(host.output()));
    std::cout << flaps << " STATE changes: the host received " << received.size()
              << " messages of the node\n";
    // The log says so in a line and a summary a minute, not a line a change.
    EXPECT_LE(lines_with(gateway_->output(), "Sparkplug primary host scada"),
              throttled_lines_at_most(flaps_start))
        << gateway_->output();

    // Births and deaths alternate, each death with the bdSeq of the birth before it, and seq
    // counts on from each NBIRTH.
    std::vector<std::string> payloads;
    for (const auto& [topic, payload] : received) payloads.push_back(payload);
    const auto decoded = tahu_decode_all(payloads);
    ASSERT_EQ(decoded.size(), received.size());
    const auto [problems, born] = check_births_and_deaths(received, decoded);
    EXPECT_GE(received.size(), 4u);
    EXPECT_TRUE(problems.empty()) << problems.size() << " problems, the first: " << problems.front()
                                  << (problems.size() > 1 ? "; " + problems[1] : "");
    EXPECT_FALSE(born);  // the clean stop's NDEATH is the last
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
