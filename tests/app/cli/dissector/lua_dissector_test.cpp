#include "eip2mqtt/app/cli/dissector/lua_dissector.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app::dissector {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Direction;
using core::plan::TagType;
using test::test_plan;
using test::test_tag;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

core::plan::ExchangePlan turbine() {
    auto speed = test_tag("SPEED", 0, TagType::real);
    speed.mutable_extras().unit = "rpm";
    auto trip = test_tag("TRIP", 4, TagType::bit);
    trip.address.bit = 6;
    auto plan = test_plan("turbine1", Direction::consume, 16,
                          {speed, trip, test_tag("COUNT", 8, TagType::lint)});
    plan.spec.producer_id = *core::wire::parse_producer_id("172.23.21.176");
    plan.spec.exchange_id = 4242;
    plan.spec.signature = {2, 5};
    return plan;
}

TEST(LuaDissector, DeclaresEachTagAsATypedFieldWithItsUnitInTheLabel) {
    const auto lua = lua_dissector({turbine()}, {});
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.turbine1.SPEED\", \"SPEED (rpm)\", \"real\", 0, 0)"))
        << lua;
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.turbine1.TRIP\", \"TRIP\", \"bit\", 4, 6)"));
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.turbine1.COUNT\", \"COUNT\", \"lint\", 8, 0)"));
}

TEST(LuaDissector, AScaledTagPassesItsScaleAndLabelsBothFields) {
    auto level = test_tag("LEVEL", 0, TagType::int_);
    level.mutable_extras().unit = "%";
    level.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::square_root, {0, 32000}, {0, 100}, 1, 0, true, std::nullopt};
    auto oil = test_tag("OIL", 2, TagType::dint);
    oil.mutable_extras().scale = core::plan::Scaling{
        core::plan::ScaleKind::gain_offset, {}, {}, 0.1, -40, false, std::nullopt};
    const auto lua = lua_dissector({test_plan("tank", Direction::consume, 8, {level, oil})}, {});
    EXPECT_TRUE(contains(lua,
                         "tag(\"eip2mqtt.tank.LEVEL\", \"LEVEL (raw)\", \"int\", 0, 0, "
                         "{ kind = \"sqrt\", raw = { 0, 32000 }, eu = { 0, 100 }, clamp = true }, "
                         "\"LEVEL (%)\")"))
        << lua;
    EXPECT_TRUE(contains(lua,
                         "tag(\"eip2mqtt.tank.OIL\", \"OIL (raw)\", \"dint\", 2, 0, "
                         "{ kind = \"gain\", gain = 0.10000000000000001, offset = -40 }, "
                         "\"OIL\")"))
        << lua;
}

TEST(LuaDissector, KeysTheExchangeByProducerAndExchangeIdWithItsRules) {
    auto plan = turbine();
    plan.timeout = std::chrono::milliseconds(3000);
    plan.clock_tolerance = std::chrono::milliseconds(500);
    const auto lua = lua_dissector({plan}, {});
    EXPECT_TRUE(contains(lua,
                         "exchange({ key = \"172.23.21.176/4242\", name = \"turbine1\", "
                         "length = 16, signature = { 2, 5 }, period_ms = 1000, "
                         "timeout_ms = 3000, clock_tolerance_ms = 500 }, function(tag)"))
        << lua;
}

TEST(LuaDissector, AnExchangeWithoutSignatureHasNone) {
    auto plan = turbine();
    plan.spec.signature = {};
    EXPECT_FALSE(contains(lua_dissector({plan}, {}), "signature = {"));
}

TEST(LuaDissector, CarriesThePortAndTheGatewayClockTolerance) {
    const auto lua = lua_dissector({}, {18300, 7938, std::chrono::milliseconds(750), "plant.yaml"});
    EXPECT_TRUE(contains(
        lua,
        "local settings = { data_port = 18300, command_port = 7938, clock_tolerance_ms = 750 }"));
    EXPECT_TRUE(contains(lua, "\"plant.yaml\""));
    EXPECT_TRUE(contains(lua, "DissectorTable.get(\"udp.port\"):add(settings.data_port, "));
}

TEST(LuaDissector, EscapesNamesIntoFieldsAndKeepsThemWholeInLabels) {
    auto plan = test_plan(
        "Bomba 1.sul", Direction::consume, 4,
        {test_tag("PRESS\xC3\x83O", 0, TagType::word), test_tag("PRESS.O", 2, TagType::word)});
    auto other = test_plan("Bomba 1 sul", Direction::consume, 4, {test_tag("X", 0, TagType::int_)});
    other.spec.exchange_id = 2;
    const auto lua = lua_dissector({plan, other}, {});
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.Bomba_1_sul.PRESS_O\", \"PRESS\\195\\131O\"")) << lua;
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.Bomba_1_sul.PRESS_O_2\", \"PRESS.O\""));
    EXPECT_TRUE(contains(lua, "tag(\"eip2mqtt.Bomba_1_sul_2.X\", \"X\", \"int\""));
    // The file is ASCII whatever the names.
    EXPECT_TRUE(std::all_of(lua.begin(), lua.end(),
                            [](char c) { return static_cast<unsigned char>(c) < 0x80; }));
}

TEST(LuaDissector, NoExchangeTakesTheExpertEntriesPart) {
    const auto lua = lua_dissector(
        {test_plan("expert", Direction::consume, 2, {test_tag("duplicate", 0, TagType::word)})},
        {});
    EXPECT_TRUE(contains(lua, "\"eip2mqtt.expert_2.duplicate\""));
}

TEST(LuaDissector, IsTheSameTextForTheSamePlans) {
    EXPECT_EQ(lua_dissector({turbine()}, {}), lua_dissector({turbine()}, {}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::dissector
