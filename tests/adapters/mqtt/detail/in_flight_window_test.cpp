#include "adapters/mqtt/detail/in_flight_window.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

TEST(InFlightWindow, GivesSequentialIdsAndCountsPending) {
    InFlightWindow<std::string> w;
    EXPECT_TRUE(w.empty());
    EXPECT_EQ(w.add("a"), 1u);
    EXPECT_EQ(w.add("b"), 2u);
    EXPECT_EQ(w.add("c"), 3u);
    EXPECT_EQ(w.pending(), 3u);
}

TEST(InFlightWindow, CompletesInAnyOrderOnce) {
    InFlightWindow<std::string> w;
    w.add("a");
    w.add("b");
    w.add("c");
    EXPECT_EQ(w.complete(2), "b");  // out of order: stays until the front completes
    EXPECT_EQ(w.pending(), 2u);
    EXPECT_FALSE(w.complete(2));  // twice: ignored
    EXPECT_EQ(w.complete(1), "a");
    EXPECT_EQ(w.complete(3), "c");
    EXPECT_TRUE(w.empty());
    EXPECT_FALSE(w.complete(1));
    EXPECT_FALSE(w.complete(4));  // never given
    EXPECT_FALSE(w.complete(0));
    EXPECT_EQ(w.add("d"), 4u);  // ids keep counting after the window emptied
    EXPECT_EQ(w.complete(4), "d");
}

TEST(InFlightWindow, AbandonHandsOverPendingInOrderAndIgnoresLateCompletions) {
    InFlightWindow<std::string> w;
    w.add("a");
    w.add("b");
    w.add("c");
    w.complete(2);
    std::vector<std::pair<std::uint64_t, std::string>> abandoned;
    w.abandon_all(
        [&](std::uint64_t id, std::string&& item) { abandoned.emplace_back(id, std::move(item)); });
    EXPECT_EQ(abandoned, (std::vector<std::pair<std::uint64_t, std::string>>{{1, "a"}, {3, "c"}}));
    EXPECT_TRUE(w.empty());
    EXPECT_FALSE(w.complete(1));  // a completion after the connection loss
    EXPECT_FALSE(w.complete(3));
    EXPECT_EQ(w.add("e"), 4u);
    EXPECT_EQ(w.pending(), 1u);
}

TEST(InFlightWindow, LongRunStaysConsistent) {
    InFlightWindow<int> w;
    std::uint64_t next_to_complete = 1;
    for (int i = 0; i < 10000; ++i) {
        w.add(i);
        if (w.pending() > 50) {
            // Complete two at a time, the second one first.
            EXPECT_EQ(w.complete(next_to_complete + 1), static_cast<int>(next_to_complete));
            EXPECT_EQ(w.complete(next_to_complete), static_cast<int>(next_to_complete - 1));
            next_to_complete += 2;
        }
    }
    EXPECT_LE(w.pending(), 51u);
}

}  // namespace
}  // namespace eip2mqtt::adapters::mqtt::detail
