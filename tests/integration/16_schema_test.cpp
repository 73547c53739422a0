// The JSON Schemas of docs/schema against the real gateway: every payload the gateway publishes
// in these scenarios (tag values of every type and quality, `_status` of every kind, `_values`,
// the metrics message, write results) is validated against the schema docs/mqtt-api.md names for
// its topic, and each kind must have been seen, so that the documentation cannot drift from the
// code unnoticed. The schemas are also shown to refuse payloads with the mistakes they exist to
// catch.

#include <chrono>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

const std::string consumed_exchanges =
    ExchangeYaml::consume("unit1", "10.0.0.1", 1)
        .length(48)
        .period_ms(100)
        .timeout_ms(400)
        .tag("RUN", "0.0", "bit")
        .tag(R"('SAY"HI\')", "0.1", "bit")  // SAY"HI\ (a quote, a backslash)
        .tag("MODE", "1.0", "byte")
        .tag("PRESSURE", "2.0", "int")
        .tag("COUNT", "5.0", "word")
        .tag("FLOW", "7.0", "dint")
        .tag("ENERGY", "11.0", "udint")
        .tag("TEMP", "15.0", "real")
        .tag("TOTAL", "19.0", "lint")
        .tag("PRECISE", "27.0", "lreal")
        .tag("NOT_A_NUMBER", "35.0", "real")
        .tag("HUGE", "39.0", "lreal")
        .str() +
    ExchangeYaml::consume("plc", "10.0.0.2", 2)
        .length(2)
        .period_ms(100)
        .timeout_ms(0)
        .key("signature", "\"2.5\"")
        .topic("area/plc")
        .tag("LEVEL", "0.0", "int")
        .str() +
    ExchangeYaml::consume("idle", "10.0.0.3", 3)
        .length(1)
        .period_ms(100)
        .tag("FLAG", "0.0", "bit")
        .str();

std::uint32_t now_seconds() {
    return static_cast<std::uint32_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                          std::chrono::system_clock::now().time_since_epoch())
                                          .count());
}

/// unit1's datagram: every type, NaN and infinity included, stamped with the current time.
std::vector<std::byte> unit1_datagram(std::uint16_t rid) {
    DatagramBuilder b("10.0.0.1", 1, 48);
    b.request_id(rid)
        .timestamp(now_seconds(), 250000000)
        .set("0.0", TagType::bit, true)
        .set("0.1", TagType::bit, rid % 2 == 0)
        .set("1.0", TagType::byte, std::uint64_t{200})
        .set("2.0", TagType::int_, std::int64_t{-32768})
        .set("5.0", TagType::word, std::uint64_t{rid})
        .set("7.0", TagType::dint, std::int64_t{-100000})
        .set("11.0", TagType::udint, std::uint64_t{4294967295})
        .set("15.0", TagType::real, -273.15f)
        .set("19.0", TagType::lint, std::int64_t{-9223372036854775807 - 1})
        .set("27.0", TagType::lreal, 65900.0)
        .set("35.0", TagType::real, std::numeric_limits<float>::quiet_NaN())
        .set("39.0", TagType::lreal, -std::numeric_limits<double>::infinity());
    return b.build();
}

/// The PLC without SNTP: its clock reads January 2000.
constexpr std::uint32_t clock_2000 = 947817150;

std::vector<std::byte> plc_datagram(std::uint16_t rid, std::uint32_t seconds,
                                    std::uint8_t major = 2, std::uint8_t minor = 5) {
    DatagramBuilder b("10.0.0.2", 2, 2);
    b.request_id(rid)
        .timestamp(seconds, 0)
        .signature(major, minor)
        .set("0.0", TagType::int_, std::int64_t{rid});
    return b.build();
}

class SchemaTest : public GatewayTest {
protected:
    /// The schema of docs/schema a topic's payloads follow (docs/mqtt-api.md, the table at the
    /// top); empty for the availability topic (plain text) and the `set` topics we publish.
    std::string schema_for(const std::string& topic, bool raw) const {
        const auto ends_with = [&](const std::string& suffix) { return topic.ends_with(suffix); };
        if (topic == metrics_topic()) return "metrics.json";
        if (ends_with("/_status")) return "status.json";
        if (ends_with("/_values")) return "values.json";
        if (ends_with("/_meta")) return "meta.json";
        if (ends_with("/set/result") || topic.starts_with("replies/")) return "write-result.json";
        if (ends_with("/set") || topic == availability_topic()) return "";
        return raw ? "tag-value-raw.json" : "tag-value.json";
    }  // namespace

    /// Validates every message recorded so far against its schema (each failure is a test
    /// failure naming topic, payload and problem); returns the payloads checked, by schema.
    std::map<std::string, std::vector<json>> validate_everything(bool raw = false) {
        const auto messages = recorder_->messages();
        std::vector<SchemaCheck> checks;
        std::vector<const Received*> checked;
        for (const auto& m : messages) {
            if (m.topic == availability_topic()) {
                EXPECT_TRUE(m.payload == "online" || m.payload == "offline") << m.payload;
                continue;
            }
            const auto schema = schema_for(m.topic, raw);
            if (schema.empty()) continue;
            checks.push_back({schema_file(schema), m.payload});
            checked.push_back(&m);
        }
        const auto problems = schema_problems(checks);
        std::map<std::string, std::vector<json>> by_schema;
        for (std::size_t i = 0; i < checks.size(); ++i) {
            EXPECT_EQ(problems[i], "") << checked[i]->topic << " " << checked[i]->payload
                                       << " against " << checks[i].schema_path;
            if (!problems[i].empty()) continue;
            const auto name = checks[i].schema_path.substr(checks[i].schema_path.rfind('/') + 1);
            by_schema[name].push_back(json::parse(checked[i]->payload));
        }
        return by_schema;
    }

    /// The values of `field` among `payloads`.
    static std::set<std::string> seen(const std::vector<json>& payloads, const std::string& field) {
        std::set<std::string> values;
        for (const auto& p : payloads) {
            if (p.is_object() && p.contains(field)) values.insert(p[field].dump());
        }
        return values;
    }

    /// Waits for the next metrics message (recorded after `from`).
    void wait_metrics(std::size_t from) {
        ASSERT_TRUE(recorder_->wait_for_message(metrics_topic(), nullptr, 10s, from).has_value());
    }
};  // namespace eip2mqtt::test

TEST_F(SchemaTest, ConsumedTagsStatusBatchAndMetricsMatchTheirSchemas) {
    start(consumed_exchanges, "  batch: true\n");
    // Good values of every type, a change (a batch), then silence: stale.
    send(unit1_datagram(1));
    send(unit1_datagram(2));
    expect_field(topic("unit1/COUNT"), "value", "2");
    expect_field(topic("unit1/TEMP"), "quality", "\"stale\"");
    expect_field(topic("unit1/_status"), "state", "\"stale\"");

    // A PLC with a clock 26 years off, which then restarts (ids go back, its clock goes on),
    // then sends another major signature: bad.
    send(plc_datagram(20000, clock_2000));
    send(plc_datagram(1, clock_2000 + 8));
    expect_field(topic("area/plc/_status"), "restarts", "1");
    send(plc_datagram(2, clock_2000 + 9, 3, 0));
    expect_field(topic("area/plc/LEVEL"), "quality", "\"bad\"");
    expect_field(topic("area/plc/_status"), "state", "\"signature_mismatch\"");
    wait_metrics(recorder_->count());

    const auto checked = validate_everything();
    const auto tags =
        checked.count("tag-value.json") ? checked.at("tag-value.json") : std::vector<json>{};
    EXPECT_EQ(seen(tags, "quality"), (std::set<std::string>{"\"good\"", "\"stale\"", "\"bad\""}));
    std::set<std::string> kinds;  // what the values were: the schema must have met each
    for (const auto& t : tags) kinds.insert(t["value"].type_name());
    EXPECT_EQ(kinds, (std::set<std::string>{"boolean", "number", "string"}));
    ASSERT_TRUE(checked.count("status.json"));
    const auto& statuses = checked.at("status.json");
    EXPECT_EQ(seen(statuses, "state"), (std::set<std::string>{"\"waiting\"", "\"ok\"", "\"stale\"",
                                                              "\"signature_mismatch\""}));
    EXPECT_EQ(seen(statuses, "clock"),
              (std::set<std::string>{"\"none\"", "\"synced\"", "\"unsynced\""}));
    ASSERT_TRUE(checked.count("values.json"));
    EXPECT_TRUE(checked.count("metrics.json"));
    // The batch message carried the tag whose name needs escaping.
    bool quoted_name = false;
    for (const auto& v : checked.at("values.json"))
        quoted_name |= v["values"].contains("SAY\"HI\\");
    EXPECT_TRUE(quoted_name);
}

TEST_F(SchemaTest, RawPayloadsMatchTheRawSchema) {
    start(consumed_exchanges, "  payload: raw\n");
    send(unit1_datagram(1));
    ASSERT_TRUE(recorder_->wait_for_message(topic("unit1/HUGE")).has_value());
    expect_field(topic("unit1/_status"), "state", "\"ok\"");
    const auto checked = validate_everything(true);
    ASSERT_TRUE(checked.count("tag-value-raw.json"));
    EXPECT_GE(checked.at("tag-value-raw.json").size(), 12u);  // and stale ones, timing permitting
    EXPECT_TRUE(checked.count("status.json"));
}

std::string produced_exchange(std::uint16_t capture_port) {
    return ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture_port))
        .period_ms(20)
        .tag("SPEED_SP", "0.0", "real", "writable: true, min: 0, max: 4000, initial: 3000")
        .tag("START", "4.0", "bit", "writable: true")
        .tag("LEVEL", "5.0", "int", "writable: true")
        .tag("LIMIT", "7.0", "word", "initial: 100")
        .str();
}

/// A write to the produced exchange and what should become of it.
struct Write {
    std::string topic;  ///< under the base topic
    std::string payload;
    bool valid_request;  ///< the request schema accepts it
    bool ok;             ///< the gateway accepts it
    bool retain = false;
};

std::vector<Write> writes_to_try() {
    const std::string big(300 * 1024, ' ');
    return {
        {"sp/SPEED_SP/set", "3100.5", true, true},
        {"sp/LEVEL/set", R"({"value":-300})", true, true},
        {"sp/START/set", "true", true, true},
        {"sp/set", R"({"SPEED_SP":3200,"START":{"value":false}})", true, true},
        {"sp/SPEED_SP/set", "4000.5", true, false},                    // above max
        {"sp/LEVEL/set", "1.5", true, false},                          // not an integer
        {"sp/NOPE/set", "1", true, false},                             // unknown tag
        {"sp/LIMIT/set", "1", true, false},                            // read-only
        {"sp/SPEED_SP/set", "100", true, false, true},                 // retained
        {"sp/START/set", "\"on\"", true, false},                       // a string, not a bit
        {"sp/LEVEL/set", "{\"value\":", false, false},                 // not JSON
        {"sp/LEVEL/set", "[1]", true, false},                          // an array, not a scalar
        {"sp/LEVEL/set", R"({"value":1,"unit":"cm"})", false, false},  // another key
        {"sp/set", "{}", false, false},                                // empty
        {"sp/set", R"({"SPEED_SP":100,"LEVEL":70000})", true, false},  // out of range
        {"sp/LEVEL/set", big + "1", true, false},                      // too large
    };
}

TEST_F(SchemaTest, WriteRequestsResultsEchoAndProducedStatusMatchTheirSchemas) {
    UdpClient capture;  // where the produced exchange goes
    start(produced_exchange(capture.port()));
    const auto writes = writes_to_try();
    for (const auto& w : writes) {
        const bool exchange_write = w.topic == "sp/set";
        const auto schema =
            schema_file(exchange_write ? "exchange-write-request.json" : "write-request.json");
        if (w.payload.size() < 1000) {  // the request schemas take what the gateway may accept
            EXPECT_EQ(schema_problem(schema, w.payload).empty(), w.valid_request) << w.payload;
        }
        const auto from = recorder_->count();
        recorder_->publish(topic(w.topic), w.payload, w.retain);
        const auto result =
            recorder_->wait_for_message(topic(w.topic + "/result"), nullptr, 10s, from);
        ASSERT_TRUE(result.has_value()) << w.topic << " " << w.payload.substr(0, 100);
        EXPECT_EQ(json::parse(result->payload)["ok"], w.ok)
            << w.payload.substr(0, 100) << " -> " << result->payload;
    }
    // MQTT 5 request/response: the result on the response topic, with correlation data; a
    // response topic on the gateway's own topics is refused, answered on `…/set/result`.
    auto from = recorder_->count();
    recorder_->publish_request(topic("sp/SPEED_SP/set"), "1234", "replies/ui", "req-42");
    const auto reply = recorder_->wait_for_message("replies/ui", nullptr, 10s, from);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(reply->correlation_data, "req-42");
    from = recorder_->count();
    recorder_->publish_request(topic("sp/SPEED_SP/set"), "1234", topic("sp/SPEED_SP"), "x");
    expect_field(topic("sp/SPEED_SP/set/result"), "error", "\"bad response topic\"", from);
    // Metrics and the produced `_status` after the writes.
    wait_metrics(recorder_->count());
    expect_field(topic("sp/_status"), "writes_applied", "5");

    const auto checked = validate_everything();
    ASSERT_TRUE(checked.count("write-result.json"));
    EXPECT_EQ(seen(checked.at("write-result.json"), "ok"),
              (std::set<std::string>{"true", "false"}));
    ASSERT_TRUE(checked.count("tag-value.json"));  // the echo of the produced values
    ASSERT_TRUE(checked.count("status.json"));
    EXPECT_EQ(seen(checked.at("status.json"), "state"), (std::set<std::string>{"\"producing\""}));
    ASSERT_TRUE(checked.count("metrics.json"));
    EXPECT_GT(checked.at("metrics.json").back()["writes_rejected"]["too_large"].get<int>(), 0);
}

/// A payload and whether its schema takes it.
struct Case {
    std::string schema;
    std::string payload;
    bool valid;
};

const std::string consumed_status =
    R"({"state":"ok","request_id":7,"received":1,"accepted":1,"missed":0,"duplicates":0,)"
    R"("out_of_order":0,"signature_mismatches":0,"length_mismatches":0,"timeouts":0,)"
    R"("restarts":0,"beyond_raw_range":0,"last_seen":1695231678000,"clock":"synced",)"
    R"("clock_offset_ms":-3})";
const std::string produced_status =
    R"({"state":"producing","request_id":1,"sent":0,"send_errors":0,"skipped_deadlines":0,)"
    R"("writes_applied":0,"writes_pending":0,"saved":true,"save_failures":0,"save_error":null})";

/// Payloads of `_status`: those marked false break one rule each.
std::vector<Case> status_cases() {
    return {
        {"status.json", consumed_status, true},
        {"status.json", produced_status, true},
        {"status.json", R"({"state":"ok"})", false},
        {"status.json", std::string(consumed_status).replace(10, 2, "fine"), false},
        {"status.json",
         std::string(consumed_status).replace(consumed_status.find("\"synced"), 7, "\"late"),
         false},
        {"status.json", std::string(consumed_status).replace(consumed_status.find("7,"), 1, "null"),
         false},
        {"status.json",
         std::string(consumed_status).replace(consumed_status.size() - 1, 1, R"(,"x":1})"), false},
        {"status.json", std::string(produced_status).replace(10, 9, "ok"), false},
        {"status.json",
         std::string(produced_status).replace(produced_status.find("1,"), 1, "70000"), false},
        {"status.json",
         std::string(produced_status)
             .replace(produced_status.find("true"), 4, "false")
             .replace(produced_status.find("null") + 1, 4, R"("write x: Input/output error")"),
         true},
        {"status.json",
         std::string(produced_status)
             .replace(produced_status.find("null"), 4, R"("write x: I/O error")"),
         false},  // a failed save leaves the image unsaved
        {"status.json",
         std::string(produced_status).replace(produced_status.find(",\"saved"), 13, ""), false},
    };
}

/// The tag values and `_values` (before), the write requests and results (after).
std::vector<Case> value_cases() {
    return {
        {"tag-value.json", R"({"value":90,"timestamp":1695231678000,"quality":"good"})", true},
        {"tag-value.json", R"({"value":"NaN","timestamp":1695231678000,"quality":"bad"})", true},
        {"tag-value.json", R"({"value":90,"timestamp":1695231678000})", false},
        {"tag-value.json", R"({"value":90,"timestamp":1695231678000,"quality":"ok"})", false},
        {"tag-value.json", R"({"value":90,"timestamp":1695231678000000,"quality":"good"})", false},
        {"tag-value.json", R"({"value":90,"timestamp":"1695231678000","quality":"good"})", false},
        {"tag-value.json", R"({"value":NaN,"timestamp":1695231678000,"quality":"good"})", false},
        {"tag-value.json", R"({"value":"B-17","timestamp":1695231678000,"quality":"good"})", true},
        {"tag-value.json", R"({"value":[[1]],"timestamp":1,"quality":"good"})", false},
        {"tag-value.json", R"({"value":1,"timestamp":1,"quality":"good","unit":"bar"})", false},
        {"tag-value-raw.json", "-273.15", true},
        {"tag-value-raw.json", "\"Infinity\"", true},
        {"tag-value-raw.json", "null", false},
        {"tag-value-raw.json", "[[1]]", false},
        {"values.json", R"({"timestamp":1,"quality":"good","values":{"A":1,"B":true}})", true},
        {"values.json", R"({"timestamp":1,"quality":"good","values":{}})", false},
        {"values.json", R"({"timestamp":1,"quality":"good","values":{"A":[1,2],"B":"x"}})", true},
        {"values.json", R"({"timestamp":1,"quality":"good","values":{"A":[[1]]}})", false},
        {"write-result.json", R"({"ok":true})", true},
        {"write-result.json", R"({"ok":false,"error":"above max 4000"})", true},
        {"write-result.json", R"({"ok":false})", false},
        {"write-result.json", R"({"ok":true,"error":"above max 4000"})", false},
        {"write-result.json", R"({"ok":"true"})", false},
        {"write-result.json", R"({"ok":true,"saved":false,"error":"not saved: write x: EIO"})",
         true},
        {"write-result.json", R"({"ok":true,"saved":true,"error":"not saved: write x: EIO"})",
         false},
        {"write-result.json", R"({"ok":true,"saved":false})", false},
        {"write-request.json", "42", true},
        {"write-request.json", R"({"value":true})", true},
        {"write-request.json", "\"B-17\"", true},
        {"write-request.json", R"({"index":2,"value":71.5})", true},
        {"write-request.json", "[[1]]", false},
        {"write-request.json", R"({"index":-1,"value":1})", false},
        {"write-request.json", R"({"value":{"value":1}})", false},
        {"exchange-write-request.json", R"({"SPEED_SP":3100,"START":{"value":true}})", true},
        {"exchange-write-request.json", R"({"SPEED_SP":null})", false},
        {"metrics.json", "{}", false},
    };
}

// The schemas are strict enough to catch the mistakes a change of the gateway could make: each
// payload below breaks one rule of docs/mqtt-api.md.
TEST(Schemas, RefusePayloadsThatBreakTheDocumentedFormat) {
    auto cases = value_cases();
    const auto status = status_cases();
    cases.insert(cases.end(), status.begin(), status.end());
    std::vector<SchemaCheck> checks;
    for (const auto& c : cases) checks.push_back({schema_file(c.schema), c.payload});
    const auto problems = schema_problems(checks);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        EXPECT_EQ(problems[i].empty(), cases[i].valid)
            << cases[i].schema << " " << cases[i].payload << ": " << problems[i];
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
