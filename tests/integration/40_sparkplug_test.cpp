// The gateway as a Sparkplug B edge node, run as the real binary against a real
// Mosquitto and real UDP, every payload read (and every command written) by Eclipse Tahu's
// JavaScript library: births with bdSeq and seq, DDATA by alias, DDEATH of a stale exchange
// and its rebirth, NCMD rebirth, DCMD writes accepted and refused, the primary host's STATE, a
// broker restart, a clean stop and a kill.

#include <signal.h>

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

std::string node_topic(const std::string& type) { return "spBv1.0/plant1/" + type + "/test-gw"; }
std::string device_topic(const std::string& type, const std::string& device) {
    return node_topic(type) + "/" + device;
}

class SparkplugTest : public GatewayTest {
protected:
    /// `timeout_ms` of the consumed exchange: long enough by default that no test but the one
    /// about staleness sees it go stale, however slow Tahu's decoding on a busy machine.
    void start_node(const std::string& sparkplug_extra = "", std::uint32_t timeout_ms = 60000) {
        capture_ = std::make_unique<UdpClient>();
        GatewayOptions options;
        options.sections = "sparkplug:\n  group_id: plant1\n" + sparkplug_extra;
        start(ExchangeYaml::consume("plant", "10.9.9.9", 1)
                      .length(8)
                      .period_ms(100)
                      .timeout_ms(timeout_ms)
                      .tag("PV", "0.0", "int", "unit: bar, description: drum pressure")
                      .tag("FLOW", "4.0", "real")
                      .str() +
                  ExchangeYaml::produce("sp", "10.1.2.3", 10,
                                        "127.0.0.1:" + std::to_string(capture_->port()))
                      .period_ms(20)
                      .tag("SPEED_SP", "0.0", "real",
                           "writable: true, min: 0, max: 4000, initial: 3000")
                      .tag("START", "4.0", "bit", "writable: true")
                      .str(),
              "", options);
    }

    void send_plant(std::uint16_t request_id, std::int64_t pv, float flow) {
        send(DatagramBuilder("10.9.9.9", 1, 8)
                 .request_id(request_id)
                 .set("0.0", TagType::int_, Value{pv})
                 .set("4.0", TagType::real, Value{flow})
                 .build());
    }

    /// Waits for the next message on `topic` after `from` and decodes it with Tahu.
    json next_on(const std::string& topic, std::size_t from, std::chrono::seconds timeout = 10s) {
        const auto message = recorder_->wait_for_message(topic, nullptr, timeout, from);
        if (!message) {
            ADD_FAILURE() << "nothing on " << topic;
            return json::object();
        }
        return tahu_decode(message->payload);
    }

    /// The index just after the next message on `topic` from index `from`; 0, and a failure,
    /// without one.
    std::size_t after_next(const std::string& topic, std::size_t from,
                           std::chrono::seconds timeout = 10s) {
        std::size_t found = 0;
        recorder_->wait_for(
            [&](const std::vector<Received>& all) {
                for (std::size_t i = from; i < all.size() && found == 0; ++i) {
                    if (all[i].topic == topic) found = i + 1;
                }
                return found != 0;
            },
            timeout);
        if (found == 0) ADD_FAILURE() << "nothing on " << topic;
        return found;
    }

    /// A host's command, encoded by Tahu.
    void command(const std::string& topic, const json& metrics, bool retain = false) {
        recorder_->publish(topic, tahu_encode({{"timestamp", 1700000000000}, {"metrics", metrics}}),
                           retain);
    }

    /// The produced exchange's next datagram's value of SPEED_SP.
    std::optional<float> next_speed_sp(float wanted) {
        const auto deadline = std::chrono::steady_clock::now() + 10s;
        while (std::chrono::steady_clock::now() < deadline) {
            const auto bytes = capture_->receive(1s);
            if (!bytes) continue;
            const auto value = std::get<float>(
                core::plan::decode_value(std::span(*bytes).subspan(32), TagType::real, {0, 0}));
            if (value == wanted) return value;
        }
        return std::nullopt;
    }

    std::unique_ptr<UdpClient> capture_;
};

TEST_F(SparkplugTest, BirthsThenDataByAliasWithSeqCountingEveryMessage) {
    start_node();
    const auto nbirth = next_on(node_topic("NBIRTH"), 0);
    EXPECT_EQ(nbirth["seq"], "0");
    EXPECT_EQ(tahu_metric(nbirth, "bdSeq")["value"], "0");
    EXPECT_EQ(tahu_metric(nbirth, "bdSeq")["type"], "Int64");
    EXPECT_EQ(tahu_metric(nbirth, "Node Control/Rebirth")["value"], false);
    EXPECT_EQ(tahu_metric(nbirth, "Exchanges/plant/state")["type"], "String");

    // The produced exchange is born with its first datagram.
    const auto sp = next_on(device_topic("DBIRTH", "sp"), 0);
    EXPECT_EQ(tahu_metric(sp, "SPEED_SP")["type"], "Float");
    EXPECT_EQ(tahu_metric(sp, "SPEED_SP")["value"], 3000);
    EXPECT_EQ(tahu_metric(sp, "START")["type"], "Boolean");
    const auto props = tahu_metric(sp, "SPEED_SP")["properties"];
    EXPECT_EQ(props["writable"]["value"], true);
    EXPECT_EQ(props["max"]["value"], 4000);
    EXPECT_EQ(props["max"]["type"], "Double");

    // The consumed exchange is born with its first datagram, every tag with its datatype.
    send_plant(1, -12, 2.5f);
    const auto plant = next_on(device_topic("DBIRTH", "plant"), 0);
    const auto pv = tahu_metric(plant, "PV");
    EXPECT_EQ(pv["type"], "Int16");
    EXPECT_EQ(pv["value"], -12);
    EXPECT_EQ(pv["properties"]["engUnit"]["value"], "bar");
    EXPECT_EQ(pv["properties"]["Documentation"]["value"], "drum pressure");
    EXPECT_EQ(tahu_metric(plant, "FLOW")["value"], 2.5);

    // A change: DDATA with that tag alone, by alias.
    const auto from = recorder_->count();
    send_plant(2, -12, 3.5f);
    const auto data = next_on(device_topic("DDATA", "plant"), from);
    ASSERT_EQ(data["metrics"].size(), 1u);
    EXPECT_FALSE(data["metrics"][0].contains("name") && !data["metrics"][0]["name"].is_null());
    EXPECT_EQ(data["metrics"][0]["alias"], tahu_metric(plant, "FLOW")["alias"]);
    EXPECT_EQ(data["metrics"][0]["value"], 3.5);

    // seq counts every message of the node from the NBIRTH's 0, with no gap. One Tahu run for
    // them all: a Node.js start each took a minute on a loaded machine.
    std::vector<std::string> payloads;
    for (const auto& m : recorder_->messages()) {
        if (!m.topic.starts_with("spBv1.0/plant1/") ||
            m.topic.find("/NDEATH/") != std::string::npos) {
            continue;
        }
        payloads.push_back(m.payload);
    }
    const auto decoded = tahu_decode_all(payloads);
    ASSERT_GE(decoded.size(), 4u);
    for (std::size_t i = 0; i < decoded.size(); ++i) {
        EXPECT_EQ(decoded[i].value("seq", json()), std::to_string(i % 256)) << i;
    }
}

TEST_F(SparkplugTest, AStaleExchangeDiesAndIsBornAgainWithItsNextDatagram) {
    start_node("", 400);
    // The node is born first: a datagram before its connection, gone stale by then, would make
    // no DBIRTH at all.
    after_next(node_topic("NBIRTH"), 0);
    send_plant(1, 5, 1.0f);
    // Positions in the recording, not its size when a wait ends: the DDEATH comes 400 ms after
    // the DBIRTH, sooner than Tahu decodes a payload on a busy machine.
    const auto born = after_next(device_topic("DBIRTH", "plant"), 0);
    ASSERT_NE(born, 0u);
    // No datagram within the timeout: the device dies.
    const auto died = after_next(device_topic("DDEATH", "plant"), born);
    ASSERT_NE(died, 0u);
    const auto death = tahu_decode(recorder_->messages().at(died - 1).payload);
    ASSERT_TRUE(death.contains("metrics")) << death.dump();
    EXPECT_TRUE(death["metrics"].empty());
    send_plant(2, 6, 1.0f);
    const auto reborn = next_on(device_topic("DBIRTH", "plant"), died);
    EXPECT_EQ(tahu_metric(reborn, "PV").value("value", json()), 6);
}

TEST_F(SparkplugTest, NcmdRebirthBringsEveryBirthAgain) {
    start_node();
    send_plant(1, 5, 1.0f);
    next_on(device_topic("DBIRTH", "plant"), 0);
    next_on(device_topic("DBIRTH", "sp"), 0);
    const auto from = recorder_->count();
    command(
        node_topic("NCMD"),
        json::array({{{"name", "Node Control/Rebirth"}, {"type", "Boolean"}, {"value", true}}}));
    const auto nbirth = next_on(node_topic("NBIRTH"), from);
    EXPECT_EQ(nbirth["seq"], "0");
    EXPECT_EQ(tahu_metric(nbirth, "bdSeq")["value"], "0");  // same connection, same bdSeq
    EXPECT_EQ(tahu_metric(next_on(device_topic("DBIRTH", "plant"), from), "PV")["value"], 5);
    next_on(device_topic("DBIRTH", "sp"), from);
}

TEST_F(SparkplugTest, ADcmdIsWrittenInOneDatagramAndEchoedByDdata) {
    start_node();
    const auto birth = next_on(device_topic("DBIRTH", "sp"), 0);
    const auto from = recorder_->count();
    // By alias, as hosts write after a birth.
    command(device_topic("DCMD", "sp"),
            json::array({{{"alias",
                           std::stoull(tahu_metric(birth, "SPEED_SP")["alias"].get<std::string>())},
                          {"type", "Float"},
                          {"value", 1234.5}}}));
    EXPECT_TRUE(next_speed_sp(1234.5f).has_value());
    const auto echo = next_on(device_topic("DDATA", "sp"), from);
    ASSERT_EQ(echo["metrics"].size(), 1u);
    EXPECT_EQ(echo["metrics"][0]["value"], 1234.5);
}

TEST_F(SparkplugTest, ARefusedOrHostileDcmdChangesNothingAndIsCounted) {
    start_node();
    next_on(device_topic("DBIRTH", "sp"), 0);
    const auto from = recorder_->count();
    command(device_topic("DCMD", "sp"),
            json::array({{{"name", "SPEED_SP"}, {"type", "Float"}, {"value", 9000}}}));  // > max
    command(device_topic("DCMD", "sp"),
            json::array({{{"name", "SPEED_SP"}, {"type", "Float"}, {"value", 10}}}), true);
    recorder_->publish(device_topic("DCMD", "sp"), std::string("\x0a\xff\xff\xff", 4));
    command(device_topic("DCMD", "plant"),
            json::array({{{"name", "PV"}, {"type", "Int16"}, {"value", 1}}}));
    // Still alive, still writable: a good command after them is applied.
    command(device_topic("DCMD", "sp"),
            json::array({{{"name", "SPEED_SP"}, {"type", "Float"}, {"value", 42}}}));
    EXPECT_TRUE(next_speed_sp(42.0f).has_value());
    const auto metrics = recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& payload) {
            const auto m = json::parse(payload, nullptr, false);
            if (!m.is_object() || !m.contains("writes_rejected")) return false;
            const auto& rejected = m["writes_rejected"];
            return rejected.value("above_max", 0) == 1 && rejected.value("retained", 0) == 1 &&
                   rejected.value("malformed", 0) == 1 && rejected.value("read_only", 0) == 1;
        },
        15s, from);
    EXPECT_TRUE(metrics.has_value());
    // None of the refused values was ever echoed.
    for (const auto& m : recorder_->messages_on(device_topic("DDATA", "sp"))) {
        const auto decoded = tahu_decode(m.payload);  // outlives the loop over its metrics
        for (const auto& value : decoded["metrics"]) {
            EXPECT_NE(value["value"], 9000);
            EXPECT_NE(value["value"], 10);
        }
    }
}

TEST_F(SparkplugTest, BirthsWaitForThePrimaryHostAndFollowItAcrossABrokerRestart) {
    start_node("  primary_host_id: scada\n");
    send_plant(1, 5, 1.0f);
    // The gateway is connected (its JSON tree says so) but the host has not said it is online.
    expect_field(topic("plant/_status"), "state", "\"ok\"");
    EXPECT_TRUE(recorder_->messages_on(node_topic("NBIRTH")).empty());
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":1})", true);
    EXPECT_EQ(tahu_metric(next_on(node_topic("NBIRTH"), 0), "bdSeq")["value"], "0");

    // The broker restarts: a new connection, a new bdSeq, every birth again once the host is
    // back online.
    recorder_.reset();
    broker_->stop();
    broker_->start();
    recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":2})", true);
    const auto nbirth = next_on(node_topic("NBIRTH"), 0, 30s);
    EXPECT_EQ(tahu_metric(nbirth, "bdSeq")["value"], "1");
    EXPECT_EQ(nbirth["seq"], "0");
    // Every device is born again with it, with the values it had.
    next_on(device_topic("DBIRTH", "sp"), 0);
    EXPECT_EQ(tahu_metric(next_on(device_topic("DBIRTH", "plant"), 0), "PV")["value"], 5);
    send_plant(2, 7, 1.0f);
    EXPECT_EQ(next_on(device_topic("DDATA", "plant"), 0)["metrics"][0]["value"], 7);

    // The host goes offline: the node says NDEATH, leaves the broker and connects again (the
    // list has one), with a new will; births once the host is back.
    const auto from = recorder_->count();
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":false,"timestamp":3})", true);
    EXPECT_EQ(tahu_metric(next_on(node_topic("NDEATH"), from), "bdSeq")["value"], "1");
    EXPECT_TRUE(gateway_->wait_for_output("MQTT (Sparkplug) session ended with", 10s));
    recorder_->publish("spBv1.0/STATE/scada", R"({"online":true,"timestamp":4})", true);
    EXPECT_EQ(tahu_metric(next_on(node_topic("NBIRTH"), from, 30s), "bdSeq")["value"], "2");
}

TEST_F(SparkplugTest, ACleanStopEndsWithNdeathAndAKillLeavesTheWill) {
    start_node();
    const auto nbirth = next_on(node_topic("NBIRTH"), 0);
    auto from = recorder_->count();
    ::kill(gateway_->pid(), SIGTERM);
    EXPECT_EQ(gateway_->wait(10s), 0);
    const auto death = next_on(node_topic("NDEATH"), from);
    EXPECT_EQ(tahu_metric(death, "bdSeq")["value"], tahu_metric(nbirth, "bdSeq")["value"]);

    start_gateway();
    const auto second = next_on(node_topic("NBIRTH"), from);
    // The state directory keeps the bdSeq: the new process's first will takes the next one.
    EXPECT_EQ(std::stoi(tahu_metric(second, "bdSeq")["value"].get<std::string>()),
              std::stoi(tahu_metric(nbirth, "bdSeq")["value"].get<std::string>()) + 1);
    from = recorder_->count();
    ::kill(gateway_->pid(), SIGKILL);
    gateway_->wait(10s);
    // The broker publishes the will once it notices (keepalive at most 1.5 x 30 s).
    const auto will = next_on(node_topic("NDEATH"), from, 60s);
    EXPECT_EQ(tahu_metric(will, "bdSeq")["value"], tahu_metric(second, "bdSeq")["value"]);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

TEST_F(SparkplugTest, WithoutTheUnsTheJsonTreeIsSilentButAvailabilityStays) {
    start_node("  uns: false\n");
    send_plant(1, 5, 1.0f);
    next_on(device_topic("DBIRTH", "plant"), 0);
    // A clean stop flushes the JSON connection and ends it with `offline`: whatever it
    // published has arrived by then.
    const auto from = recorder_->count();
    ::kill(gateway_->pid(), SIGTERM);
    EXPECT_EQ(gateway_->wait(10s), 0);
    ASSERT_TRUE(recorder_
                    ->wait_for_message(
                        availability_topic(), [](const std::string& p) { return p == "offline"; },
                        10s, from)
                    .has_value());
    for (const auto& m : recorder_->messages()) {
        if (!m.topic.starts_with(std::string(base_topic) + "/")) continue;
        EXPECT_TRUE(m.topic == availability_topic()) << m.topic;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
