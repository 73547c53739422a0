#include "eip2mqtt/core/quality/report_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace eip2mqtt::core::quality {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using plan::Value;

MonoTime at(std::chrono::milliseconds offset) { return MonoTime{} + offset; }

/// A tag's filter with the deadband and refresh of its spec, as ExchangeConsumer passes them.
struct TagFilter {
    double deadband;
    std::chrono::seconds refresh;
    ReportFilter filter{};

    bool should_publish(const Value& value, Quality quality, MonoTime now) const {
        return filter.should_publish(value, quality, now, deadband, refresh);
    }
    void published(const Value& value, Quality quality, MonoTime now) {
        filter.published(value, quality, now);
    }
    void reset() { filter.reset(); }
    std::optional<MonoTime> refresh_due() const { return filter.refresh_due(refresh); }
    const Value* last_value() const { return filter.last_value(); }
};

TEST(ReportFilter, FirstValueIsPublished) {
    const TagFilter filter{0.0, 60s};
    EXPECT_TRUE(filter.should_publish(Value{std::int64_t{0}}, Quality::good, at(0ms)));
    EXPECT_EQ(filter.last_value(), nullptr);
    EXPECT_EQ(filter.refresh_due(), std::nullopt);
}

TEST(ReportFilter, ShouldPublishDoesNotRecord) {
    TagFilter filter{0.0, 60s};
    const Value v{std::int64_t{1}};
    EXPECT_TRUE(filter.should_publish(v, Quality::good, at(0ms)));
    EXPECT_TRUE(filter.should_publish(v, Quality::good, at(1ms)));
    filter.published(v, Quality::good, at(1ms));
    EXPECT_FALSE(filter.should_publish(v, Quality::good, at(2ms)));
    ASSERT_NE(filter.last_value(), nullptr);
    EXPECT_EQ(*filter.last_value(), v);
}

TEST(ReportFilter, ZeroDeadbandPublishesAnyChange) {
    TagFilter filter{0.0, 60s};
    filter.published(Value{1.0f}, Quality::good, at(0ms));
    EXPECT_FALSE(filter.should_publish(Value{1.0f}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{std::nextafter(1.0f, 2.0f)}, Quality::good, at(1ms)));
}

TEST(ReportFilter, DeadbandIsStrict) {
    TagFilter filter{0.5, 60s};
    filter.published(Value{10.0}, Quality::good, at(0ms));
    EXPECT_FALSE(filter.should_publish(Value{10.5}, Quality::good, at(1ms)));
    EXPECT_FALSE(filter.should_publish(Value{9.5}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{10.51}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{9.49}, Quality::good, at(1ms)));
}

TEST(ReportFilter, DeadbandCountsFromTheLastPublication) {
    TagFilter filter{5.0, 60s};
    filter.published(Value{std::int64_t{100}}, Quality::good, at(0ms));
    // Creeping by 3 each time: measured from 100, not from the previous sample.
    EXPECT_FALSE(filter.should_publish(Value{std::int64_t{103}}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{std::int64_t{106}}, Quality::good, at(2ms)));
}

TEST(ReportFilter, DeadbandOnUnsignedIntegers) {
    TagFilter filter{2.0, 60s};
    filter.published(Value{std::uint64_t{10}}, Quality::good, at(0ms));
    EXPECT_FALSE(filter.should_publish(Value{std::uint64_t{8}}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{std::uint64_t{7}}, Quality::good, at(1ms)));
}

TEST(ReportFilter, BoolsIgnoreTheDeadband) {
    TagFilter filter{5.0, 60s};
    filter.published(Value{false}, Quality::good, at(0ms));
    EXPECT_TRUE(filter.should_publish(Value{true}, Quality::good, at(1ms)));
    EXPECT_FALSE(filter.should_publish(Value{false}, Quality::good, at(1ms)));
}

TEST(ReportFilter, NanIsAChangeOnceOnly) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    TagFilter filter{1.0, 60s};
    filter.published(Value{1.0f}, Quality::good, at(0ms));
    EXPECT_TRUE(filter.should_publish(Value{nan}, Quality::good, at(1ms)));
    filter.published(Value{nan}, Quality::good, at(1ms));
    EXPECT_FALSE(filter.should_publish(Value{nan}, Quality::good, at(2ms)));
    EXPECT_TRUE(filter.should_publish(Value{1.0f}, Quality::good, at(2ms)));
}

TEST(ReportFilter, InfinityIsComparedExactly) {
    const double inf = std::numeric_limits<double>::infinity();
    TagFilter filter{1.0, 60s};
    filter.published(Value{inf}, Quality::good, at(0ms));
    EXPECT_FALSE(filter.should_publish(Value{inf}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{-inf}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{1e300}, Quality::good, at(1ms)));
}

TEST(ReportFilter, QualityChangeIsPublished) {
    TagFilter filter{10.0, 60s};
    filter.published(Value{1.0}, Quality::good, at(0ms));
    EXPECT_TRUE(filter.should_publish(Value{1.0}, Quality::stale, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{1.0}, Quality::bad, at(1ms)));
}

TEST(ReportFilter, ValueTypeChangeIsPublished) {
    TagFilter filter{10.0, 60s};
    filter.published(Value{std::int64_t{1}}, Quality::good, at(0ms));
    EXPECT_TRUE(filter.should_publish(Value{std::uint64_t{1}}, Quality::good, at(1ms)));
    EXPECT_TRUE(filter.should_publish(Value{1.0}, Quality::good, at(1ms)));
}

TEST(ReportFilter, RefreshRepublishesAnUnchangedValue) {
    TagFilter filter{0.0, 60s};
    filter.published(Value{true}, Quality::good, at(1000ms));
    EXPECT_EQ(filter.refresh_due(), at(61000ms));
    EXPECT_FALSE(filter.should_publish(Value{true}, Quality::good, at(60999ms)));
    EXPECT_TRUE(filter.should_publish(Value{true}, Quality::good, at(61000ms)));
    filter.published(Value{true}, Quality::good, at(61000ms));
    EXPECT_EQ(filter.refresh_due(), at(121000ms));
    EXPECT_FALSE(filter.should_publish(Value{true}, Quality::good, at(61001ms)));
}

TEST(ReportFilter, ZeroRefreshNeverRepublishes) {
    TagFilter filter{0.0, 0s};
    filter.published(Value{true}, Quality::good, at(0ms));
    EXPECT_EQ(filter.refresh_due(), std::nullopt);
    EXPECT_FALSE(filter.should_publish(Value{true}, Quality::good, at(24h)));
}

TEST(ReportFilter, ResetPublishesTheNextValue) {
    TagFilter filter{0.0, 60s};
    filter.published(Value{true}, Quality::good, at(0ms));
    filter.reset();
    EXPECT_EQ(filter.last_value(), nullptr);
    EXPECT_EQ(filter.refresh_due(), std::nullopt);
    EXPECT_TRUE(filter.should_publish(Value{true}, Quality::good, at(1ms)));
}

TEST(ReportFilter, DeadbandAndRefreshAreTheCallers) {
    ReportFilter filter;
    filter.published(Value{10.0}, Quality::good, at(0ms));
    EXPECT_FALSE(filter.should_publish(Value{11.0}, Quality::good, at(1ms), 2.0, 60s));
    EXPECT_TRUE(filter.should_publish(Value{11.0}, Quality::good, at(1ms), 0.5, 60s));
    EXPECT_FALSE(filter.should_publish(Value{10.0}, Quality::good, at(10s), 0.0, 60s));
    EXPECT_TRUE(filter.should_publish(Value{10.0}, Quality::good, at(10s), 0.0, 10s));
    EXPECT_EQ(filter.refresh_due(10s), at(10s));
    EXPECT_EQ(filter.refresh_due(60s), at(60s));
}

TEST(ReportFilter, EveryQualityIsRecorded) {
    // The "never published" marker shares the quality's byte: no real quality may read as it.
    for (const auto quality : {Quality::good, Quality::stale, Quality::bad}) {
        ReportFilter filter;
        filter.published(Value{true}, quality, at(0ms));
        ASSERT_NE(filter.last_value(), nullptr);
        EXPECT_FALSE(filter.should_publish(Value{true}, quality, at(1ms), 0.0, 60s));
    }
}

TEST(ReportFilter, AnArrayMovesWhenAnyElementMovesBeyondTheBand) {
    TagFilter tag{0.5, 0s};
    const auto list = [](float a, float b) { return plan::make_list({Value{a}, Value{b}}); };
    tag.published(list(10.0f, 20.0f), Quality::good, at(0ms));
    EXPECT_FALSE(tag.should_publish(list(10.4f, 19.6f), Quality::good, at(1ms)));
    EXPECT_TRUE(tag.should_publish(list(10.0f, 20.6f), Quality::good, at(1ms)));
    EXPECT_TRUE(tag.should_publish(list(9.4f, 20.0f), Quality::good, at(1ms)));
    EXPECT_TRUE(tag.should_publish(plan::make_list({Value{10.0f}}), Quality::good, at(1ms)));
}

TEST(ReportFilter, ATextChangesOrDoesNot) {
    TagFilter tag{5.0, 0s};  // a band means nothing to a text
    tag.published(plan::make_text("B-1"), Quality::good, at(0ms));
    EXPECT_FALSE(tag.should_publish(plan::make_text("B-1"), Quality::good, at(1ms)));
    EXPECT_TRUE(tag.should_publish(plan::make_text("B-2"), Quality::good, at(1ms)));
}

TEST(ReportFilter, FitsThirtyTwoBytes) {
    // One per consumed tag, 100,000 in a large plant (see
    // docs/decisions/0001-configurations-of-100000-tags.md).
    EXPECT_LE(sizeof(ReportFilter), 32u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::quality
