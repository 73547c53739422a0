#include "eip2mqtt/core/config/config.hpp"

#include <gtest/gtest.h>

#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Marks, AddKeepsTheFirstMarkOfAKey) {
    Marks marks;
    EXPECT_TRUE(marks.add("name", at(4, 7)));
    EXPECT_TRUE(marks.add("type", at(5, 7)));
    EXPECT_FALSE(marks.add("name", at(6, 7)));  // a duplicate: the loader reports it
    EXPECT_TRUE(marks.contains("name"));
    EXPECT_FALSE(marks.contains("address"));
    EXPECT_EQ(marks.of("name").line, 4);
    EXPECT_EQ(marks.keys.size(), 2u);
}

TEST(Marks, OfFallsBackToTheNode) {
    Marks marks;
    marks.node = at(3, 5);
    marks.add("name", at(4, 7));
    EXPECT_EQ(marks.of("name").line, 4);
    EXPECT_EQ(marks.of("name").column, 7);
    EXPECT_EQ(marks.of("length").line, 3);
    EXPECT_EQ(marks.of("length").column, 5);
}

TEST(MakePlans, OnePlanPerExchangeWithEveryTag) {
    const auto c = valid();
    const auto plans = make_plans(c);
    ASSERT_EQ(plans.size(), 2u);
    EXPECT_EQ(plans[0].topic, "acme/site/turbine1");
    ASSERT_EQ(plans[0].spec.tags.size(), 2u);
    EXPECT_EQ(plans[0].spec.tags[1].name, "PRESSAO");
    EXPECT_EQ(plans[0].tag_topic(plans[0].tags[1]), "acme/site/turbine1/PRESSAO");
    EXPECT_EQ(plans[0].timeout, 300ms);
    EXPECT_EQ(plans[1].tag_topic(plans[1].tags[0]), "acme/site/setpoints/SPEED_SP");
    EXPECT_EQ(plans[1].length, 16);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
