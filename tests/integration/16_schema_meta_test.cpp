// `{exchange}/_meta` from the real gateway: published retained at start, checked against
// docs/schema/meta.json, published again by a reload that changes the exchange (and only then),
// cleared when the exchange goes; checked against the schema before and after the reload.

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/schema_check.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using nlohmann::json;
using namespace std::chrono_literals;

std::string turbine(const std::string& speed_unit) {
    return ExchangeYaml::consume("turbine", "10.0.0.1", 1)
        .length(8)
        .period_ms(100)
        .topic("area/turbine")
        .key("signature", "\"1.0\"")
        .tag("SPEED", "0.0", "real",
             "unit: " + speed_unit +
                 ", description: shaft speed, deadband: 0.5, min: 0, "
                 "max: 4000")
        .tag("RUN", "4.3", "bit")
        .str();
}

std::string setpoints(std::uint16_t port) {
    return ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(port))
        .period_ms(50)
        .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000")
        .str();
}

std::string steady() {
    return ExchangeYaml::consume("steady", "10.0.0.2", 2)
        .length(2)
        .tag("LEVEL", "0.0", "int")
        .str();
}

class MetaTest : public GatewayTest {
protected:
    /// The next non-empty `_meta` of `exchange_topic` after message `from`, checked against the
    /// schema; null JSON (and a test failure) when none came.
    json meta_of(const std::string& exchange_topic, std::size_t from = 0) {
        const auto m = recorder_->wait_for_message(
            topic(exchange_topic + "/_meta"), [](const std::string& p) { return !p.empty(); }, 10s,
            from);
        EXPECT_TRUE(m.has_value()) << exchange_topic;
        if (!m) return nullptr;
        EXPECT_EQ(schema_problem(schema_file("meta.json"), m->payload), "") << m->payload;
        return json::parse(m->payload);
    }

    /// Every `_meta` the start publishes: the turbine's tags in full, the produced exchange's
    /// destination and writable tag, and steady's.
    void expect_described_at_start(std::uint16_t capture_port) {
        const auto before = meta_of("area/turbine");
        EXPECT_EQ(before["exchange"], "turbine");
        EXPECT_EQ(before["direction"], "consume");
        EXPECT_EQ(before["producer_id"], "10.0.0.1");
        EXPECT_EQ(before["exchange_id"], 1);
        EXPECT_EQ(before["length"], 8);
        EXPECT_EQ(before["period_ms"], 100);
        EXPECT_EQ(before["signature"], "1.0");
        const auto& speed = before["tags"]["SPEED"];
        EXPECT_EQ(speed["type"], "real");
        EXPECT_EQ(speed["address"], "0.0");
        EXPECT_EQ(speed["unit"], "rpm");
        EXPECT_EQ(speed["description"], "shaft speed");
        EXPECT_EQ(speed["writable"], false);
        EXPECT_EQ(speed["min"], 0);
        EXPECT_EQ(speed["max"], 4000);
        EXPECT_EQ(speed["deadband"], 0.5);
        EXPECT_EQ(before["tags"]["RUN"]["address"], "4.3");
        const auto produced = meta_of("sp");
        EXPECT_EQ(produced["direction"], "produce");
        EXPECT_EQ(produced["destination"], "127.0.0.1:" + std::to_string(capture_port));
        EXPECT_EQ(produced["tags"]["SPEED_SP"]["writable"], true);
        meta_of("steady");
    }

    /// A consumer arriving after the reload gets the descriptions from the broker's retained
    /// store: the turbine's new one and steady's, none for sp.
    void expect_retained_after_reload() {
        MqttRecorder late(broker_->url(),
                          {topic("sp/_meta"), topic("area/turbine/_meta"), topic("steady/_meta")},
                          "late-subscriber");
        ASSERT_TRUE(late.wait_for([](const auto& all) { return all.size() >= 2; }));
        std::vector<SchemaCheck> checks;
        for (const auto& m : late.messages()) {
            EXPECT_TRUE(m.retained) << m.topic;
            EXPECT_NE(m.topic, topic("sp/_meta")) << m.payload;
            checks.push_back({schema_file("meta.json"), m.payload});
        }
        for (const auto& problem : schema_problems(checks)) EXPECT_EQ(problem, "");
        EXPECT_EQ(json::parse(late.messages_on(topic("area/turbine/_meta"))
                                  .at(0)
                                  .payload)["tags"]["SPEED"]["unit"],
                  "rad/s");
    }
};

TEST_F(MetaTest, DescribesEachExchangeAtStartAndAfterAReloadThatChangesItMatchingTheSchema) {
    UdpClient capture;  // where the produced exchange goes
    start(turbine("rpm") + setpoints(capture.port()) + steady());

    expect_described_at_start(capture.port());

    // The turbine's unit changes, sp goes, steady stays as it was.
    const auto from = recorder_->count();
    rewrite_exchanges(turbine("rad/s") + steady());
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();

    const auto after = meta_of("area/turbine", from);
    EXPECT_EQ(after["tags"]["SPEED"]["unit"], "rad/s");
    EXPECT_TRUE(
        recorder_
            ->wait_for_message(
                topic("sp/_meta"), [](const std::string& p) { return p.empty(); }, 10s, from)
            .has_value())
        << "the removed exchange's _meta is cleared";
    // The restarted turbine's `_status` is queued after the reload's `_meta` changes.
    ASSERT_TRUE(recorder_->wait_for_message(topic("area/turbine/_status"), nullptr, 10s, from));
    std::size_t steady_metas = 0;
    const auto messages = recorder_->messages();
    for (std::size_t i = from; i < messages.size(); ++i) {
        steady_metas += messages[i].topic == topic("steady/_meta");
    }
    EXPECT_EQ(steady_metas, 0u) << "an unchanged exchange's _meta is not published again";

    expect_retained_after_reload();
}

/// The JSON examples of a page of docs/ marked `<!-- schema: NAME -->` on the line before their
/// ```json fence, with the schema each names.
std::vector<SchemaCheck> marked_examples(const std::string& page) {
    std::ifstream in(std::string(EIP2MQTT_SOURCE_DIR) + "/docs/" + page);
    std::vector<SchemaCheck> checks;
    std::string line;
    std::string schema;
    const std::string marker = "<!-- schema: ";
    while (std::getline(in, line)) {
        if (line.starts_with(marker)) {
            schema = line.substr(marker.size(), line.find(' ', marker.size()) - marker.size());
        } else if (line == "```json" && !schema.empty()) {
            std::string text;
            while (std::getline(in, line) && line != "```") text += line + "\n";
            checks.push_back({schema_file(schema), text});
            schema.clear();
        }
    }
    return checks;
}

TEST(Schemas, TheHistorianGuideAndTheApiExamplesMatchTheirSchemas) {
    auto checks = marked_examples("historians.md");
    ASSERT_EQ(checks.size(), 2u) << "a values.json and a meta.json example";
    const auto api = marked_examples("mqtt-api.md");
    ASSERT_EQ(api.size(), 1u) << "the _meta example";
    checks.insert(checks.end(), api.begin(), api.end());
    const auto problems = schema_problems(checks);
    for (std::size_t i = 0; i < checks.size(); ++i) {
        EXPECT_EQ(problems[i], "") << checks[i].schema_path << "\n" << checks[i].json_text;
    }
    // And the schema refuses what a historian could not use.
    const std::string meta = checks[1].json_text;
    const std::vector<std::pair<std::string, std::string>> broken{
        {"\"type\":\"real\"", "\"type\":\"float\""},
        {"\"address\":\"4.0\"", "\"address\":\"4\""},
        {"\"writable\":false,", ""},
        {"\"timeout_ms\":300", "\"timeout_ms\":null"},  // a consumed exchange has a timeout
    };
    std::vector<SchemaCheck> wrong;
    for (const auto& [from, to] : broken) {
        auto text = meta;
        const auto at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        wrong.push_back({schema_file("meta.json"), text.replace(at, from.size(), to)});
    }
    const auto refused = schema_problems(wrong);
    for (std::size_t i = 0; i < wrong.size(); ++i) {
        EXPECT_NE(refused[i], "") << wrong[i].json_text;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
