#include "eip2mqtt/core/ring.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core {
namespace {

TEST(Ring, FirstInFirstOutAcrossTheWrap) {
    Ring<int> ring;
    EXPECT_TRUE(ring.empty());
    for (int i = 0; i < 10; ++i) ring.push_back(i);
    for (int i = 0; i < 8; ++i) {
        EXPECT_EQ(ring.front(), i);
        ring.pop_front();
    }
    // Head at 8 of 16 slots: these wrap to the start of the buffer.
    for (int i = 10; i < 20; ++i) EXPECT_FALSE(ring.push_back(i));
    EXPECT_EQ(ring.size(), 12u);
    EXPECT_EQ(ring.capacity(), 16u);
    EXPECT_EQ(ring[0], 8);
    EXPECT_EQ(ring.back(), 19);
    for (int i = 8; i < 20; ++i) {
        EXPECT_EQ(ring.front(), i);
        ring.pop_front();
    }
    EXPECT_TRUE(ring.empty());
}

TEST(Ring, GrowsByDoublingAndKeepsTheOrder) {
    Ring<int> ring;
    for (int i = 0; i < 10; ++i) ring.push_back(i);
    for (int i = 0; i < 5; ++i) ring.pop_front();
    int grew = 0;
    for (int i = 10; i < 40; ++i) grew += ring.push_back(i) ? 1 : 0;
    EXPECT_EQ(grew, 2);  // 35 elements: 16 -> 32 -> 64 slots
    EXPECT_EQ(ring.capacity(), 64u);
    EXPECT_EQ(ring.size(), 35u);
    for (std::size_t i = 0; i < ring.size(); ++i) EXPECT_EQ(ring[i], static_cast<int>(i) + 5);
}

TEST(Ring, ReleaseFreesOnlyWhenEmpty) {
    Ring<std::string> ring;
    ring.push_back(std::string(100, 'x'));
    ring.push_back("b");
    ring.pop_front();
    ring.push_back("c");
    EXPECT_EQ(ring.front(), "b");
    ring.release();  // not empty: kept
    EXPECT_EQ(ring.capacity(), 16u);
    ring.clear();
    EXPECT_TRUE(ring.empty());
    EXPECT_EQ(ring.capacity(), 16u);
    ring.release();
    EXPECT_EQ(ring.capacity(), 0u);
    ring.push_back("again");
    EXPECT_EQ(ring.front(), "again");
}

}  // namespace
}  // namespace eip2mqtt::core
