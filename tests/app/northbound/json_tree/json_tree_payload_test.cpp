// The payloads of the JSON topic tree (app/northbound/json_tree/json_tree_payload.hpp).

#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"

#include <gtest/gtest.h>

#include "tests/support/schema_check.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

std::string json_string(std::string_view text) {
    std::string out = "x";  // appended to, never replaced
    append_json_string(out, text);
    return out;
}

TEST(JsonString, QuotesAndEscapesWhatJsonRequires) {
    EXPECT_EQ(json_string("PRESSAO"), R"(x"PRESSAO")");
    // Tag names may hold quotes and backslashes (`_values` was invalid JSON).
    EXPECT_EQ(json_string(R"(SAY"HI\)"), R"(x"SAY\"HI\\")");
    EXPECT_EQ(json_string(std::string("A\x01"
                                      "B\n\t",
                                      5)),
              R"(x"A\u0001B\n\t")");  // the short escapes where JSON has one
    EXPECT_EQ(json_string("Pressão/°C"), "x\"Pressão/°C\"");  // UTF-8 as is
    EXPECT_EQ(json_string(""), R"(x"")");
}

TEST(WriteResult, OkOrTheErrorAsAJsonString) {
    EXPECT_EQ(format_write_result(), R"({"ok":true})");
    EXPECT_EQ(format_write_result("reloaded"), R"({"error":"reloaded","ok":false})");
    EXPECT_EQ(format_write_result(R"(tag "A\B" is read-only)"),
              R"({"error":"tag \"A\\B\" is read-only","ok":false})");
}

TEST(WriteResult, BytesThatAreNotUtf8AreReplacedSoTheResultStaysJson) {
    // A client may name a tag with any bytes; the refusal quotes the name.
    EXPECT_EQ(format_write_result("unknown tag \xff\xfe"),
              "{\"error\":\"unknown tag \xef\xbf\xbd\xef\xbf\xbd\",\"ok\":false}");
}

TEST(ProducedStatus, CarriesEveryCounterAndTheState) {
    ProducedStatus status;
    status.request_id = 7;
    status.counters.sent = 100;
    status.counters.send_errors = 2;
    status.counters.skipped_deadlines = 3;
    status.counters.writes_applied = 4;
    status.writes_pending = 5;
    EXPECT_EQ(format_produced_status_payload(status),
              R"({"state":"producing","request_id":7,"sent":100,"send_errors":2,)"
              R"("skipped_deadlines":3,"writes_applied":4,"save_failures":0,)"
              R"("writes_pending":5,"saved":true,"save_error":null})");
    status.paused = true;
    EXPECT_EQ(format_produced_status_payload(status).substr(0, 18), R"({"state":"paused",)");
}

TEST(ProducedStatus, CarriesAFailedSaveQuotedAsJson) {
    ProducedStatus status;
    status.saved = false;
    status.counters.save_failures = 3;
    status.save_error = "write /s/\"x\".image.tmp: No space left on device";
    const auto payload = format_produced_status_payload(status);
    EXPECT_NE(payload.find(R"("save_failures":3,"writes_pending":0,"saved":false,)"
                           R"("save_error":"write /s/\"x\".image.tmp: No space left on device"})"),
              std::string::npos)
        << payload;
    EXPECT_EQ(test::schema_problem(test::schema_file("status.json"), payload), "") << payload;
}

TEST(WriteResult, AppliedButUnsavedSaysSo) {
    const auto payload = format_write_result_unsaved("fdatasync /s/sp.image: Input/output error");
    EXPECT_EQ(payload, R"({"error":"not saved: fdatasync /s/sp.image: Input/output error",)"
                       R"("ok":true,"saved":false})");
    EXPECT_EQ(test::schema_problem(test::schema_file("write-result.json"), payload), "") << payload;
}

using core::plan::ScaleKind;
using core::plan::Scaling;
using core::plan::TagType;
using core::plan::Value;
using core::quality::Quality;

core::plan::TagSpec level_tag(bool publish_raw) {
    core::plan::TagSpec tag;
    tag.name = "level";
    tag.type = TagType::int_;
    tag.mutable_extras().scale =
        Scaling{ScaleKind::linear, {0, 32000}, {0, 100}, 1, 0, true, std::nullopt};
    tag.mutable_extras().publish_raw = publish_raw;
    return tag;
}

std::string tag_payload(const core::plan::TagSpec& tag, const Value& raw,
                        core::config::PayloadFormat format = core::config::PayloadFormat::json) {
    std::string out = "left over";
    format_tag_payload(out, "turbine1", tag, raw, Quality::good, 1700000000000, format);
    return out;
}

TEST(TagPayload, AScaledTagPublishesItsEngineeringValue) {
    const auto tag = level_tag(false);
    EXPECT_EQ(tag_payload(tag, Value{std::int64_t{8000}}),
              R"({"value":25.0,"timestamp":1700000000000,"quality":"good"})");
    EXPECT_EQ(tag_payload(tag, Value{std::int64_t{8000}}, core::config::PayloadFormat::raw),
              "25.0");
}

TEST(TagPayload, ALimitIsFlaggedAndPublishRawAddsTheWiresValue) {
    const auto payload = tag_payload(level_tag(true), Value{std::int64_t{32767}});
    EXPECT_EQ(payload,
              R"({"value":100.0,"timestamp":1700000000000,"quality":"good","limit":"high",)"
              R"("raw":32767})");
    EXPECT_EQ(test::schema_problem(test::schema_file("tag-value.json"), payload), "") << payload;
    EXPECT_EQ(tag_payload(level_tag(true), Value{std::int64_t{-1}}),
              R"({"value":0.0,"timestamp":1700000000000,"quality":"good","limit":"low",)"
              R"("raw":-1})");
}

TEST(TagPayload, AnUnscaledTagIsAsBefore) {
    core::plan::TagSpec tag;
    tag.type = TagType::real;
    EXPECT_EQ(tag_payload(tag, Value{1.5f}),
              R"({"value":1.5,"timestamp":1700000000000,"quality":"good"})");
}

TEST(TagPayload, EachProfileHasItsShapeAndItsSchema) {
    using core::config::PayloadFormat;
    const auto tag = level_tag(false);
    const Value raw{std::int64_t{8000}};
    EXPECT_EQ(tag_payload(tag, raw, PayloadFormat::value), "25.0");
    const auto umh = tag_payload(tag, raw, PayloadFormat::umh);
    EXPECT_EQ(umh, R"({"value":25.0,"timestamp_ms":1700000000000})");
    const auto kepware = tag_payload(tag, raw, PayloadFormat::kepware);
    EXPECT_EQ(kepware, R"({"timestamp":1700000000000,"values":[{"id":"turbine1.level","v":25.0,)"
                       R"("q":true,"t":1700000000000}]})");
    const auto problems =
        test::schema_problems({{test::schema_file("tag-value-umh.json"), umh},
                               {test::schema_file("kepware.json"), kepware},
                               {test::schema_file("tag-value-bare.json"), "25.0"}});
    for (const auto& problem : problems) EXPECT_EQ(problem, "");
}

TEST(TagPayload, TheValueProfilePublishesAStringBareAndKepwareSaysAStaleValueIsNotGood) {
    using core::config::PayloadFormat;
    core::plan::TagSpec text;
    text.name = "BATCH";
    text.type = TagType::string;
    text.count = 8;
    EXPECT_EQ(tag_payload(text, Value{core::plan::Text("B-12")}, PayloadFormat::value), "B-12");
    EXPECT_EQ(tag_payload(text, Value{core::plan::Text("B-12")}, PayloadFormat::raw), "\"B-12\"");
    std::string out;
    format_tag_payload(out, "x", text, Value{core::plan::Text("a\"b")}, Quality::stale, 5,
                       PayloadFormat::kepware);
    EXPECT_EQ(out, R"({"timestamp":5,"values":[{"id":"x.BATCH","v":"a\"b","q":false,"t":5}]})");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
