// Payload profiles end to end (docs/mqtt-api.md, "Payload profiles"): the real binary against a
// real Mosquitto and real UDP, one gateway per profile. Each data message matches its profile's
// schema, and writes in the profile's own shape reach the produced exchange.

#include <nlohmann/json.hpp>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using core::plan::Value;
using nlohmann::json;
using namespace std::chrono_literals;

std::string exchanges() {
    return ExchangeYaml::consume("line", "10.0.0.1", 1)
               .length(12)
               .period_ms(100)
               .timeout_ms(60000)
               .tag("COUNT", "0.0", "dint")
               .tag("BATCH", "4.0", "string", "length: 8")
               .str() +
           ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:9")
               .period_ms(100)
               .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 3000")
               .tag("RECIPE", "4.0", "string", "length: 8, writable: true")
               .str();
}

std::vector<std::byte> line(std::uint16_t rid, std::int64_t count, const std::string& batch) {
    DatagramBuilder builder("10.0.0.1", 1, 12);
    builder.request_id(rid);
    builder.set("0.0", TagType::dint, Value{count});
    for (std::size_t i = 0; i < batch.size() && i < 8; ++i) {
        builder.data()[4 + i] = static_cast<std::byte>(batch[i]);
    }
    return builder.build();
}

class PayloadProfilesTest : public GatewayTest {
protected:
    /// The first message on `suffix` whose payload `holds`; fails the test when none comes.
    std::string first_on(const std::string& suffix,
                         const std::function<bool(const std::string&)>& holds) {
        const auto m = recorder_->wait_for_message(topic(suffix), holds, 10s);
        EXPECT_TRUE(m.has_value()) << suffix;
        return m ? m->payload : std::string();
    }
    static std::function<bool(const std::string&)> has(std::string text) {
        return [text](const std::string& p) { return p.find(text) != std::string::npos; };
    }
    static void expect_schema(const std::string& schema, const std::vector<std::string>& texts) {
        std::vector<SchemaCheck> checks;
        for (const auto& text : texts) checks.push_back({schema_file(schema), text});
        const auto problems = schema_problems(checks);
        for (std::size_t i = 0; i < problems.size(); ++i) {
            EXPECT_EQ(problems[i], "") << texts[i];
        }
    }
};

TEST_F(PayloadProfilesTest, UmhPublishesValueAndTimestampMsAndTakesItsOwnWrites) {
    start(exchanges(), "  payload: umh\n");
    send(line(1, 42, "B-1"));
    const auto count = first_on("line/COUNT", has("42"));
    EXPECT_EQ(json::parse(count)["value"], 42);
    const auto batch = first_on("line/BATCH", has("B-1"));
    expect_schema("tag-value-umh.json", {count, batch});
    EXPECT_EQ(write_result("sp/SPEED_SP/set", R"({"value": 2500, "timestamp_ms": 1700000000000})"),
              R"({"ok":true})");
    expect_schema("tag-value-umh.json", {first_on("sp/SPEED_SP", has("2500.0"))});
}

TEST_F(PayloadProfilesTest, KepwarePublishesOneMessagePerExchangeAndTakesItsRecords) {
    start(exchanges(), "  payload: kepware\n");
    send(line(1, 42, "B-1"));
    const auto values = first_on("line/_values", has("line.COUNT"));
    const auto parsed = json::parse(values);
    ASSERT_EQ(parsed["values"].size(), 2u) << values;
    EXPECT_EQ(parsed["values"][0]["id"], "line.COUNT");
    EXPECT_EQ(parsed["values"][0]["v"], 42);
    EXPECT_EQ(parsed["values"][0]["q"], true);
    EXPECT_EQ(parsed["values"][1]["v"], "B-1");
    expect_schema("kepware.json", {values, first_on("line/COUNT", has("42"))});
    EXPECT_EQ(write_result("sp/set",
                           R"([{"id": "sp.SPEED_SP", "v": 2400}, {"id": "RECIPE", "v": "R7"}])"),
              R"({"ok":true})");
    expect_schema("kepware.json", {first_on("sp/SPEED_SP", has("2400.0"))});
    EXPECT_EQ(write_result("sp/SPEED_SP/set", R"({"v": 2300})"), R"({"ok":true})");
    const auto refused = json::parse(write_result("sp/set", R"([{"id": "sp.NOPE", "v": 1}])"));
    EXPECT_EQ(refused["ok"], false);
}

TEST_F(PayloadProfilesTest, ValuePublishesTheBareValueAndTakesTextBack) {
    start(exchanges(), "  payload: value\n");
    send(line(1, 42, "B-1"));
    const auto count = first_on("line/COUNT", has("42"));
    EXPECT_EQ(count, "42");
    expect_schema("tag-value-bare.json", {count});
    EXPECT_EQ(first_on("line/BATCH", has("B-1")), "B-1");
    EXPECT_EQ(write_result("sp/RECIPE/set", "R-9"), R"({"ok":true})");
    EXPECT_EQ(first_on("sp/RECIPE", has("R-9")), "R-9");
    EXPECT_EQ(write_result("sp/SPEED_SP/set", "2600"), R"({"ok":true})");
    EXPECT_EQ(json::parse(write_result("sp/SPEED_SP/set", "fast"))["ok"], false);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
