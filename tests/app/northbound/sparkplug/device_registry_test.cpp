// The edge node's devices alone: one per running exchange with its topics and alias base, a
// kept exchange keeps its values through a reload, a produced one is up once every value is
// known, a command's metric finds its tag by alias or name, and DDATA is filled by alias
// without allocating once its payload has held a batch as large.

#include "eip2mqtt/app/northbound/sparkplug/device_registry.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"
#include "tests/app/support/test_plan.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::CommandMetric;
using adapters::sparkplug::Payload;
using core::plan::Direction;
using core::plan::Value;
using core::quality::Quality;
using test::sparkplug_plan;

class DeviceRegistryTest : public ::testing::Test {
protected:
    DeviceRegistryTest() { registry_.exchanges_changed({{&in_}, {&out_}}); }

    core::plan::ExchangePlan in_ = sparkplug_plan("in", Direction::consume);
    core::plan::ExchangePlan out_ = sparkplug_plan("out", Direction::produce);
    DeviceRegistry registry_{"plant1", "gw1"};
};

TEST_F(DeviceRegistryTest, EachExchangeIsADeviceWithItsTopicsAndAliasBase) {
    ASSERT_EQ(registry_.devices().size(), 2u);
    auto* in = registry_.find(&in_);
    auto* out = registry_.find(std::string("out"));
    ASSERT_NE(in, nullptr);
    ASSERT_NE(out, nullptr);
    EXPECT_EQ(in, registry_.find(std::string("in")));
    EXPECT_EQ(registry_.find(std::string("nowhere")), nullptr);
    EXPECT_FALSE(in->produced);
    EXPECT_TRUE(out->produced);
    EXPECT_EQ(in->alias_base, std::uint64_t{1} << 32);
    EXPECT_EQ(out->alias_base, std::uint64_t{2} << 32);
    EXPECT_EQ(in->birth_topic, "spBv1.0/plant1/DBIRTH/gw1/in");
    EXPECT_EQ(in->data_topic, "spBv1.0/plant1/DDATA/gw1/in");
    EXPECT_EQ(in->death_topic, "spBv1.0/plant1/DDEATH/gw1/in");
}

TEST_F(DeviceRegistryTest, AProducedDeviceIsUpOnceEveryValueIsKnownAndAKeptOneKeepsThem) {
    const std::vector<TagSample> some{{0, Value{std::int64_t{7}}}};
    const std::vector<TagSample> rest{{1, Value{1.5f}}, {2, Value{std::int64_t{0}}}};
    auto& out = *registry_.find(&out_);
    EXPECT_FALSE(DeviceRegistry::record(out, {out_, Quality::good, 10, false, some}));
    EXPECT_TRUE(DeviceRegistry::record(out, {out_, Quality::good, 20, false, rest}));
    EXPECT_FALSE(DeviceRegistry::record(out, {out_, Quality::good, 30, false, rest}));
    EXPECT_EQ(out.timestamps[0], 10);
    EXPECT_EQ(out.timestamps[2], 30);

    out.born = true;
    registry_.exchanges_changed({{}, {&out_}});  // "in" removed: "out" moves up
    auto& kept = *registry_.find(&out_);
    EXPECT_EQ(registry_.find(&in_), nullptr);
    EXPECT_EQ(kept.alias_base, std::uint64_t{1} << 32);
    EXPECT_FALSE(kept.born);
    EXPECT_TRUE(kept.up);
    EXPECT_EQ(kept.values[0], Value{std::int64_t{7}});
}

TEST_F(DeviceRegistryTest, ACommandsMetricFindsItsTagByAliasElseByName) {
    const auto& out = *registry_.find(&out_);
    CommandMetric metric;
    metric.alias = out.alias_base + 1;
    EXPECT_EQ(DeviceRegistry::tag_of(out, metric), 1u);
    metric.alias = out.alias_base + 3;  // past its tags
    EXPECT_EQ(DeviceRegistry::tag_of(out, metric), std::nullopt);
    metric.name = "C";
    EXPECT_EQ(DeviceRegistry::tag_of(out, metric), 2u);
    metric.alias = (std::uint64_t{1} << 32) + 0;  // another device's alias
    metric.name = "D";
    EXPECT_EQ(DeviceRegistry::tag_of(out, metric), std::nullopt);
}

TEST_F(DeviceRegistryTest, DdataIsFilledByAliasWithoutAllocatingOnceAsLarge) {
    auto& in = *registry_.find(&in_);
    const std::vector<TagSample> two{{0, Value{std::int64_t{7}}}, {2, Value{std::int64_t{9}}}};
    const std::vector<TagSample> one{{1, Value{2.5f}}};
    Payload payload;
    DeviceRegistry::fill_data(in, {in_, Quality::good, 50, false, two}, true, payload);
    ASSERT_EQ(payload.metrics.size(), 2u);
    EXPECT_EQ(payload.metrics[1].alias, in.alias_base + 2);
    EXPECT_TRUE(payload.metrics[1].name.empty());
    EXPECT_TRUE(payload.metrics[1].historical);
    EXPECT_EQ(payload.metrics[1].timestamp_ms, 50u);
    const auto* storage = payload.metrics.data();
    DeviceRegistry::fill_data(in, {in_, Quality::good, 60, false, one}, false, payload);
    ASSERT_EQ(payload.metrics.size(), 1u);
    EXPECT_EQ(payload.metrics.data(), storage);
    EXPECT_EQ(payload.metrics[0].alias, in.alias_base + 1);
    EXPECT_FALSE(payload.metrics[0].historical);
    EXPECT_EQ(payload.metrics[0].datatype, adapters::sparkplug::DataType::float32);
}

TEST_F(DeviceRegistryTest, ADbirthNamesEveryTagWithItsPropertiesAndANullForAnUnknownValue) {
    auto& out = *registry_.find(&out_);
    const std::vector<TagSample> a{{0, Value{std::int64_t{7}}}};
    DeviceRegistry::record(out, {out_, Quality::good, 10, false, a});
    Payload payload;
    DeviceRegistry::fill_birth(out, payload, 99);
    ASSERT_EQ(payload.metrics.size(), 3u);
    EXPECT_EQ(payload.metrics[0].name, "A");
    EXPECT_EQ(payload.metrics[0].alias, out.alias_base);
    EXPECT_EQ(payload.metrics[0].timestamp_ms, 10u);
    EXPECT_EQ(payload.metrics[1].timestamp_ms, 99u);
    EXPECT_FALSE(payload.metrics[1].value.has_value());
    std::vector<std::string> keys;
    for (const auto& property : payload.metrics[0].properties) keys.push_back(property.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"engUnit", "writable", "max"}));
}

TEST(DeviceRegistryScaled, AScaledTagIsBornAndReportedInUnitsWithItsRange) {
    using core::plan::ScaleKind;
    using core::plan::Scaling;
    using core::plan::TagType;
    auto level = test::test_tag("LEVEL", 0, TagType::int_);
    level.mutable_extras().unit = "%";
    level.mutable_extras().scale =
        Scaling{ScaleKind::linear, {0, 32000}, {0, 100}, 1, 0, false, std::nullopt};
    auto counts = test::test_tag("COUNTS", 2, TagType::real);
    counts.mutable_extras().scale =
        Scaling{ScaleKind::gain_offset, {}, {}, 2, 0, false, TagType::dint};
    const auto plan = test::test_plan("tank", Direction::consume, 8, {level, counts});
    DeviceRegistry registry{"plant1", "gw1"};
    registry.exchanges_changed({{&plan}, {}});
    auto& device = *registry.find(&plan);
    const std::vector<TagSample> samples{{0, Value{std::int64_t{8000}}},
                                         {1, Value{std::numeric_limits<float>::quiet_NaN()}}};
    DeviceRegistry::record(device, {plan, Quality::good, 10, false, samples});
    Payload birth;
    DeviceRegistry::fill_birth(device, birth, 99);
    ASSERT_EQ(birth.metrics.size(), 2u);
    EXPECT_EQ(birth.metrics[0].datatype, adapters::sparkplug::DataType::float64);
    EXPECT_EQ(birth.metrics[0].value, adapters::sparkplug::MetricValue{Value{25.0}});
    std::vector<std::string> keys;
    for (const auto& property : birth.metrics[0].properties) keys.push_back(property.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"engUnit", "engLow", "engHigh"}));
    EXPECT_EQ(birth.metrics[0].properties[2].value, adapters::sparkplug::MetricValue{Value{100.0}});
    // An integer type_eu: the metric's datatype; a NaN has no integer, so is_null.
    EXPECT_EQ(birth.metrics[1].datatype, adapters::sparkplug::DataType::int32);
    EXPECT_FALSE(birth.metrics[1].value.has_value());

    const std::vector<TagSample> next{{1, Value{3.0f}}};
    Payload data;
    DeviceRegistry::fill_data(device, {plan, Quality::good, 20, false, next}, false, data);
    ASSERT_EQ(data.metrics.size(), 1u);
    EXPECT_EQ(data.metrics[0].datatype, adapters::sparkplug::DataType::int32);
    EXPECT_EQ(data.metrics[0].value, adapters::sparkplug::MetricValue{Value{std::int64_t{6}}});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
