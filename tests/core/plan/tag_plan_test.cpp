#include "eip2mqtt/core/plan/tag_plan.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TagSpec pressure() {
    TagSpec spec;
    spec.name = "PRESSAO";
    spec.address = {2, 0};
    spec.type = TagType::int_;
    return spec;
}

TEST(TagSpec, FitsSixtyFourBytes) {
    // One per tag, 100,000 in a large plant (see
    // docs/decisions/0001-configurations-of-100000-tags.md).
    EXPECT_LE(sizeof(TagSpec), 64u);
    EXPECT_EQ(sizeof(TagPlan), sizeof(TagSpec));
}

TEST(TagSpec, ExtrasReadTheirDefaultsWhenNoneIsSet) {
    const auto spec = pressure();
    EXPECT_EQ(spec.unit(), "");
    EXPECT_EQ(spec.min(), std::nullopt);
    EXPECT_EQ(spec.max(), std::nullopt);
    EXPECT_EQ(spec.initial(), std::nullopt);
    EXPECT_EQ(spec.max_writes_per_s(), 0.0);
}

TEST(TagSpec, ExtrasAreReadBack) {
    auto spec = pressure();
    spec.mutable_extras().unit = "bar";
    spec.mutable_extras().min = -1.0;
    spec.mutable_extras().max = 10.0;
    spec.mutable_extras().initial = Value{std::int64_t{3}};
    spec.mutable_extras().max_writes_per_s = 2.5;
    EXPECT_EQ(spec.unit(), "bar");
    EXPECT_EQ(spec.min(), -1.0);
    EXPECT_EQ(spec.max(), 10.0);
    EXPECT_EQ(spec.initial(), Value{std::int64_t{3}});
    EXPECT_EQ(spec.max_writes_per_s(), 2.5);
}

TEST(TagSpec, CopiesKeepTheirOwnExtras) {
    auto spec = pressure();
    spec.mutable_extras().max = 10.0;
    auto copy = spec;
    copy.mutable_extras().max = 20.0;
    EXPECT_EQ(spec.max(), 10.0);
    EXPECT_EQ(copy.max(), 20.0);
}

TEST(TagSpec, EqualityComparesContents) {
    // Reload keeps an exchange whose plan compares equal: extras written with their defaults
    // (a YAML `unit: ""`) must equal none, and a change in any extra must show.
    const auto plain = pressure();
    auto written = pressure();
    written.mutable_extras().unit = "";
    EXPECT_EQ(plain, written);
    auto other = pressure();
    other.mutable_extras().unit = "bar";
    EXPECT_NE(plain, other);
    auto same = pressure();
    same.mutable_extras().unit = "bar";
    EXPECT_EQ(other, same);
    same.mutable_extras().max_writes_per_s = 1;
    EXPECT_NE(other, same);
    auto renamed = pressure();
    renamed.name = "PRESSURE";
    EXPECT_NE(plain, renamed);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
