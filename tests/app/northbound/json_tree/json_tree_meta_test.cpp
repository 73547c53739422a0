// `{exchange}/_meta`: what a consumer of the JSON tree learns of an exchange and its tags.

#include "eip2mqtt/app/northbound/json_tree/json_tree_meta.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Direction;
using core::plan::TagType;
using json = nlohmann::ordered_json;  // keeps the payload's order

TEST(JsonTreeMeta, EveryTagWithItsTypeAddressUnitLimitsAndDeadbandInConfigurationOrder) {
    auto speed = test::test_tag("SPEED", 0, TagType::real);
    speed.deadband = 0.5;
    auto& extras = speed.mutable_extras();
    extras.unit = "rpm";
    extras.description = "shaft speed";
    extras.min = 0;
    extras.max = 4000;
    auto run = test::test_tag("RUN", 4, TagType::bit);
    run.address.bit = 3;
    auto plan = test::test_plan("turbine", Direction::consume, 8, {speed, run}, "t1/turbine");
    plan.spec.signature = {1, 2};

    const auto meta = json::parse(format_meta_payload(plan));
    EXPECT_EQ(plan.meta_topic, "acme/t1/turbine/_meta");
    EXPECT_EQ(meta["exchange"], "turbine");
    EXPECT_EQ(meta["direction"], "consume");
    EXPECT_EQ(meta["producer_id"], "10.0.0.1");
    EXPECT_EQ(meta["exchange_id"], 1);
    EXPECT_EQ(meta["length"], 8);
    EXPECT_EQ(meta["period_ms"], 1000);
    EXPECT_EQ(meta["signature"], "1.2");
    EXPECT_EQ(meta["timeout_ms"], 3000);  // 3 periods
    EXPECT_TRUE(meta["destination"].is_null());

    const auto& tags = meta["tags"];
    ASSERT_EQ(tags.size(), 2u);
    EXPECT_EQ(tags.begin().key(), "SPEED");  // configuration order, not sorted
    const auto& s = tags["SPEED"];
    EXPECT_EQ(s["type"], "real");
    EXPECT_EQ(s["address"], "0.0");
    EXPECT_EQ(s["unit"], "rpm");
    EXPECT_EQ(s["description"], "shaft speed");
    EXPECT_EQ(s["writable"], false);
    EXPECT_EQ(s["min"], 0);
    EXPECT_EQ(s["max"], 4000);
    EXPECT_EQ(s["deadband"], 0.5);
    const auto& r = tags["RUN"];
    EXPECT_EQ(r["type"], "bit");
    EXPECT_EQ(r["address"], "4.3");
    for (const auto* absent : {"unit", "description", "min", "max"}) {
        EXPECT_TRUE(r[absent].is_null()) << absent;
    }
}

TEST(JsonTreeMeta, AProducedExchangeSaysWhereItGoesAndWhichTagsAreWritable) {
    const auto plan = test::test_plan("sp", Direction::produce, 4,
                                      {test::test_tag("SETPOINT", 0, TagType::dint, true)});
    const auto meta = json::parse(format_meta_payload(plan));
    EXPECT_EQ(meta["direction"], "produce");
    EXPECT_EQ(meta["destination"], "127.0.0.1");
    EXPECT_TRUE(meta["timeout_ms"].is_null());
    EXPECT_TRUE(meta["signature"].is_null());
    EXPECT_EQ(meta["tags"]["SETPOINT"]["writable"], true);
}

TEST(JsonTreeMeta, IsWrittenAsAJsonLibraryWritesItAndNeverCarriesABrokenByte) {
    auto speed = test::test_tag("SPEED", 0, TagType::real);
    speed.deadband = 2;
    auto& extras = speed.mutable_extras();
    extras.unit =
        "\xb0"
        "C";  // a Latin-1 degree sign, from a point list exported on Windows
    extras.description = "say \"hi\"\\ \t";
    extras.min = -1.5e-7;
    extras.max = 1e21;
    auto plan = test::test_plan("t", Direction::consume, 4, {speed});
    const auto payload = format_meta_payload(plan);

    const auto meta = json::parse(payload);  // throws on a byte that is not UTF-8
    EXPECT_EQ(meta.dump(), payload);         // the same bytes: numbers, escapes, no spaces
    const auto& s = meta["tags"]["SPEED"];
    EXPECT_EQ(s["unit"],
              "\xef\xbf\xbd"
              "C");  // U+FFFD in place of the byte
    EXPECT_EQ(s["description"], "say \"hi\"\\ \t");
    EXPECT_TRUE(s["deadband"].is_number_float());
    EXPECT_EQ(s["deadband"], 2.0);
    EXPECT_EQ(s["min"], -1.5e-7);
    EXPECT_EQ(s["max"], 1e21);
}

TEST(JsonTreeMeta, AScaledTagSaysItsScaleAndPercentDeadband) {
    auto level = test::test_tag("LEVEL", 0, TagType::int_);
    level.deadband = 0.5;
    auto& extras = level.mutable_extras();
    extras.scale = core::plan::Scaling{
        core::plan::ScaleKind::linear, {0, 32000}, {0, 100}, 1, 0, true, std::nullopt};
    extras.deadband_percent = 0.5;
    extras.publish_raw = true;
    auto oil = test::test_tag("OIL", 2, TagType::dint);
    oil.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::gain_offset, {}, {}, 0.1, -40, false, TagType::real};
    const auto plan = test::test_plan("tank", Direction::consume, 8, {level, oil});
    const auto text = format_meta_payload(plan);
    EXPECT_EQ(test::schema_problem(test::schema_file("meta.json"), text), "") << text;
    const auto meta = json::parse(text);
    const auto& l = meta["tags"]["LEVEL"];
    EXPECT_EQ(l["type"], "int");
    EXPECT_EQ(l["deadband"], 0.5);
    EXPECT_EQ(l["deadband_percent"], 0.5);
    EXPECT_EQ(l["publish_raw"], true);
    EXPECT_EQ(l["scale"], json::parse(R"({"kind":"linear","raw":[0.0,32000.0],"eu":[0.0,100.0],)"
                                      R"("clamp":true,"type_eu":"lreal"})"));
    const auto& o = meta["tags"]["OIL"];
    EXPECT_EQ(o["scale"],
              json::parse(R"({"kind":"gain","gain":0.1,"offset":-40.0,"type_eu":"real"})"));
    EXPECT_FALSE(o.contains("deadband_percent"));
    EXPECT_FALSE(o.contains("publish_raw"));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::json_tree
