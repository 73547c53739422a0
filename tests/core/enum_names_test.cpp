#include "eip2mqtt/core/enum_names.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/decode_error.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/config_keys.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"
#include "eip2mqtt/core/exchange/wire_survey.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/quality/quality.hpp"
#include "eip2mqtt/core/redundancy/image_follow.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"
#include "tests/support/enumerators.hpp"

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

enum class Colour : std::uint8_t { red, green, blue };
constexpr auto colour_names = enum_names<Colour>("red", "green", "blue");

TEST(EnumNames, NamesEachValueInOrder) {
    EXPECT_EQ(colour_names.size(), 3U);
    EXPECT_EQ(colour_names.name_of(Colour::red), "red");
    EXPECT_EQ(colour_names.name_of(Colour::blue), "blue");
    EXPECT_EQ(colour_names.name_of(static_cast<Colour>(3)), "unknown");
    EXPECT_EQ(colour_names.values(), (std::array{Colour::red, Colour::green, Colour::blue}));
}

TEST(EnumNames, ParsesOnlyAWholeName) {
    EXPECT_EQ(colour_names.parse("green"), Colour::green);
    EXPECT_EQ(colour_names.parse("Green"), std::nullopt);
    EXPECT_EQ(colour_names.parse("gree"), std::nullopt);
    EXPECT_EQ(colour_names.parse(""), std::nullopt);
}

TEST(EnumNames, TheEnumeratorSearchTellsAMissingName) {
    enum class Gap : std::uint8_t { a, b, c = 4 };
    EXPECT_TRUE((test::enumerators_are_first<Colour, 3>()));
    EXPECT_FALSE((test::enumerators_are_first<Colour, 2>()));
    EXPECT_FALSE((test::enumerators_are_first<Colour, 4>()));
    EXPECT_FALSE((test::enumerators_are_first<Gap, 3>()));
}

TEST(EnumNames, EveryCoreEnumeratorHasAName) {
    test::expect_every_value_named(quality::quality_names);
    test::expect_every_value_named(wire::drop_reason_names);
    test::expect_every_value_named(exchange::clock_state_names);
    test::expect_every_value_named(exchange::destination_kind_names);
    test::expect_every_value_named(exchange::consume_state_names);
    test::expect_every_value_named(plan::direction_names);
    test::expect_every_value_named(plan::timestamp_source_names);
    test::expect_every_value_named(plan::tag_type_names);
    test::expect_every_value_named(write::write_error_names);
    test::expect_every_value_named(config::reload_rule_names);
    test::expect_every_value_named(config::payload_format_names);
    test::expect_every_value_named(command::command_status_names);
    test::expect_every_value_named(command::decode_error_names);
    test::expect_every_value_named(redundancy::follow_verdict_names);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
