#include "eip2mqtt/core/redundancy/sample_window.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::core::redundancy {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using quality::Quality;

const MonoTime t0{std::chrono::hours(1)};

class SampleWindowTest : public ::testing::Test {
protected:
    /// Sample `n`: request id n, tag 0 = n, received n * 20 ms after t0.
    void record(std::uint16_t n, std::uint8_t change = 0) {
        const plan::TagSample tag{0, plan::Value{std::uint64_t{n}}};
        pushed_out_ += window_.record({n, 0, 0, change}, at(n), 1000 + n, Quality::good, {&tag, 1});
    }
    static MonoTime at(std::uint16_t n) { return t0 + n * 20ms; }
    /// The request ids of the samples after `watermark`, as of `now`.
    std::vector<std::uint16_t> after(const std::optional<SampleKey>& watermark, MonoTime now) {
        const auto start = window_.after(watermark, now);
        found_ = start.watermark_found;
        std::vector<std::uint16_t> ids;
        for (auto i = start.first; i < window_.size(); ++i)
            ids.push_back(window_[i].key.request_id);
        return ids;
    }

    SampleWindow window_{{1000ms, 100, 1 << 20}};
    std::size_t pushed_out_ = 0;
    bool found_ = false;
};

TEST(SampleWindowBounds, TwiceTheTakeoverAndTwiceItsSamplesAtThePeriod) {
    const auto bounds = window_bounds(1000ms, 20ms, 4096);
    EXPECT_EQ(bounds.span, 2000ms);
    EXPECT_EQ(bounds.max_samples, 2u * 100 + 2);
    EXPECT_EQ(bounds.max_bytes, 4096u);
    EXPECT_EQ(window_bounds(1000ms, 1h, 4096).max_samples, 16u);
    EXPECT_EQ(window_bounds(600000ms, 2ms, 4096).max_samples, max_window_samples);
}

TEST_F(SampleWindowTest, TheSamplesAfterTheWatermarkOldestFirst) {
    for (std::uint16_t n = 1; n <= 10; ++n) record(n);
    EXPECT_EQ(after(SampleKey{7}, at(10)), (std::vector<std::uint16_t>{8, 9, 10}));
    EXPECT_TRUE(found_);
    EXPECT_EQ(window_[window_.size() - 1].timestamp_ms, 1010);
    EXPECT_EQ(std::get<std::uint64_t>(window_[window_.size() - 1].tags.at(0).value), 10u);
    EXPECT_TRUE(after(SampleKey{10}, at(10)).empty());
}

TEST_F(SampleWindowTest, EverySampleWithoutAWatermark) {
    for (std::uint16_t n = 1; n <= 3; ++n) record(n);
    EXPECT_EQ(after(std::nullopt, at(3)), (std::vector<std::uint16_t>{1, 2, 3}));
    EXPECT_FALSE(found_);
}

TEST_F(SampleWindowTest, AWatermarkTheStandbyDidNotReceiveIsPlacedByItsRequestId) {
    for (std::uint16_t n : {1, 2, 3, 5, 6}) record(n);
    EXPECT_EQ(after(SampleKey{4}, at(6)), (std::vector<std::uint16_t>{5, 6}));
    EXPECT_FALSE(found_);
    // Older than every sample held: all of them.
    EXPECT_EQ(after(SampleKey{0}, at(6)), (std::vector<std::uint16_t>{1, 2, 3, 5, 6}));
}

TEST_F(SampleWindowTest, AWatermarkFoundByNameSurvivesAnUntimedRestart) {
    // The producer restarted at request id 0: by the request ids alone, 0 and 1 are older than
    // 500, but the window holds 500 and knows what came after it.
    for (std::uint16_t n : {498, 499, 500, 0, 1}) {
        const plan::TagSample tag{0, plan::Value{std::uint64_t{n}}};
        window_.record({n}, t0, 0, Quality::good, {&tag, 1});
    }
    EXPECT_EQ(after(SampleKey{500}, t0), (std::vector<std::uint16_t>{0, 1}));
    EXPECT_TRUE(found_);
}

TEST_F(SampleWindowTest, AChangeOfQualityIsASampleOfItsOwn) {
    record(1);
    record(1, 1);
    record(2);
    EXPECT_EQ(after(SampleKey{1}, at(2)), (std::vector<std::uint16_t>{1, 2}));
    EXPECT_EQ(window_[1].key.change, 1);
    EXPECT_EQ(after(SampleKey{1, 0, 0, 1}, at(2)), (std::vector<std::uint16_t>{2}));
}

TEST_F(SampleWindowTest, SamplesOlderThanTheSpanGo) {
    for (std::uint16_t n = 1; n <= 60; ++n) record(n);
    // At sample 60 (1.2 s), those received more than 1 s before: 1 to 9.
    EXPECT_EQ(after(std::nullopt, at(60)).front(), 10);
    EXPECT_TRUE(after(std::nullopt, at(60) + 2s).empty());
    EXPECT_EQ(pushed_out_, 0u);
}

TEST_F(SampleWindowTest, TheCountBoundPushesOutTheOldestAndCountsThem) {
    window_.set_bounds({1000ms, 4, 1 << 20}, at(0));
    for (std::uint16_t n = 1; n <= 6; ++n) record(n);
    EXPECT_EQ(after(std::nullopt, at(6)), (std::vector<std::uint16_t>{3, 4, 5, 6}));
    EXPECT_EQ(pushed_out_, 2u);
}

TEST_F(SampleWindowTest, TheByteBoundPushesOutTheOldestAndCountsThem) {
    window_.set_bounds({1000ms, 100, 3 * SampleWindow::bytes_of(1)}, at(0));
    for (std::uint16_t n = 1; n <= 5; ++n) record(n);
    EXPECT_EQ(after(std::nullopt, at(5)), (std::vector<std::uint16_t>{3, 4, 5}));
    EXPECT_EQ(window_.bytes(), 3 * SampleWindow::bytes_of(1));
    EXPECT_EQ(pushed_out_, 2u);
    // Narrower bounds apply at once.
    window_.set_bounds({1000ms, 100, SampleWindow::bytes_of(1)}, at(5));
    EXPECT_EQ(after(std::nullopt, at(5)), (std::vector<std::uint16_t>{5}));
}

TEST_F(SampleWindowTest, ASampleLargerThanTheWholeBoundIsNotKept) {
    window_.set_bounds({1000ms, 100, SampleWindow::bytes_of(1)}, at(0));
    const std::vector<plan::TagSample> tags(2, plan::TagSample{0, plan::Value{true}});
    EXPECT_EQ(window_.record({1}, at(1), 0, Quality::good, tags), 1u);
    EXPECT_EQ(window_.size(), 0u);
    EXPECT_EQ(window_.bytes(), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::redundancy
