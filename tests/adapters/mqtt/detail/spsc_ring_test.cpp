#include "adapters/mqtt/detail/spsc_ring.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <thread>

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

TEST(SpscRing, FirstInFirstOutUpToItsCapacity) {
    SpscRing<std::string, 4> ring;
    EXPECT_TRUE(ring.empty());
    for (int i = 0; i < 4; ++i) {
        std::string item = "item " + std::to_string(i);
        EXPECT_TRUE(ring.try_push(item));
        EXPECT_TRUE(item.empty());  // moved in
    }
    std::string refused = "fifth";
    EXPECT_FALSE(ring.try_push(refused));
    EXPECT_EQ(refused, "fifth");  // untouched when full
    EXPECT_EQ(ring.size(), 4u);
    std::string out;
    for (int i = 0; i < 4; ++i) {
        ASSERT_TRUE(ring.try_pop(out));
        EXPECT_EQ(out, "item " + std::to_string(i));
    }
    EXPECT_FALSE(ring.try_pop(out));
    EXPECT_TRUE(ring.empty());
}

TEST(SpscRing, TwoThreadsSeeEveryItemInOrder) {
    // A producer and a consumer on their own threads, each spinning on a full or empty ring:
    // every value arrives once and in order (ASan would see a torn slot). Bounded by the count.
    constexpr std::uint64_t count = 200000;
    SpscRing<std::uint64_t, 64> ring;
    std::thread producer([&] {
        for (std::uint64_t i = 1; i <= count; ++i) {
            std::uint64_t item = i;
            while (!ring.try_push(item)) std::this_thread::yield();
        }
    });
    std::uint64_t expected = 1;
    std::uint64_t out_of_order = 0;
    while (expected <= count) {
        std::uint64_t item = 0;
        if (!ring.try_pop(item)) {
            std::this_thread::yield();
            continue;
        }
        if (item != expected) ++out_of_order;
        expected = item + 1;
    }
    producer.join();
    EXPECT_EQ(out_of_order, 0u);
    EXPECT_TRUE(ring.empty());
}

}  // namespace
}  // namespace eip2mqtt::adapters::mqtt::detail
