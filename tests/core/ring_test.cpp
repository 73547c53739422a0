#include "eip2mqtt/core/ring.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

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

TEST(Ring, CopiesAndMovesKeepTheElementsInOrder) {
    Ring<std::string> ring;
    for (int i = 0; i < 20; ++i) ring.push_back("element number " + std::to_string(i));
    for (int i = 0; i < 15; ++i) ring.pop_front();  // the rest wraps inside the buffer
    for (int i = 20; i < 30; ++i) ring.push_back("element number " + std::to_string(i));
    Ring<std::string> copy = ring;
    ASSERT_EQ(copy.size(), 15u);
    for (std::size_t i = 0; i < copy.size(); ++i) {
        EXPECT_EQ(copy[i], "element number " + std::to_string(i + 15));
    }
    Ring<std::string> moved = std::move(ring);
    EXPECT_EQ(moved.front(), "element number 15");
    EXPECT_EQ(moved.back(), "element number 29");
    copy = moved;
    EXPECT_EQ(copy.back(), "element number 29");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
