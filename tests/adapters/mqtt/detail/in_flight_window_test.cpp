#include "adapters/mqtt/detail/in_flight_window.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(InFlightWindow, GivesSequentialIdsAndCountsPending) {
    InFlightWindow<std::string> w;
    EXPECT_TRUE(w.empty());
    EXPECT_EQ(w.add("a", false), 1u);
    EXPECT_EQ(w.add("b", false), 2u);
    EXPECT_EQ(w.add("c", false), 3u);
    EXPECT_EQ(w.pending(), 3u);
}

TEST(InFlightWindow, CompletesInAnyOrderOnce) {
    InFlightWindow<std::string> w;
    w.add("a", false);
    w.add("b", false);
    w.add("c", false);
    EXPECT_EQ(w.complete(2), "b");  // out of order: stays until the front completes
    EXPECT_EQ(w.pending(), 2u);
    EXPECT_FALSE(w.complete(2));  // twice: ignored
    EXPECT_EQ(w.complete(1), "a");
    EXPECT_EQ(w.complete(3), "c");
    EXPECT_TRUE(w.empty());
    EXPECT_FALSE(w.complete(1));
    EXPECT_FALSE(w.complete(4));  // never given
    EXPECT_FALSE(w.complete(0));
    EXPECT_EQ(w.add("d", false), 4u);  // ids keep counting after the window emptied
    EXPECT_EQ(w.complete(4), "d");
}

TEST(InFlightWindow, AbandonHandsOverPendingInOrderAndIgnoresLateCompletions) {
    InFlightWindow<std::string> w;
    w.add("a", false);
    w.add("b", false);
    w.add("c", false);
    w.complete(2);
    std::vector<std::pair<std::uint64_t, std::string>> abandoned;
    w.abandon_all(
        [&](std::uint64_t id, std::string&& item) { abandoned.emplace_back(id, std::move(item)); });
    EXPECT_EQ(abandoned, (std::vector<std::pair<std::uint64_t, std::string>>{{1, "a"}, {3, "c"}}));
    EXPECT_TRUE(w.empty());
    EXPECT_FALSE(w.complete(1));  // a completion after the connection loss
    EXPECT_FALSE(w.complete(3));
    EXPECT_EQ(w.add("e", false), 4u);
    EXPECT_EQ(w.pending(), 1u);
}

TEST(InFlightWindow, CountsWhatAwaitsAnAcknowledgementApart) {
    // The broker's Receive Maximum bounds QoS >= 1 publications only.
    InFlightWindow<std::string> w;
    const auto qos0 = w.add("a", false);
    const auto qos1 = w.add("b", true);
    w.add("c", true);
    EXPECT_EQ(w.pending(), 3u);
    EXPECT_EQ(w.pending_acknowledged(), 2u);
    w.complete(qos0);
    EXPECT_EQ(w.pending_acknowledged(), 2u);
    w.complete(qos1);
    w.complete(qos1);  // a late second completion changes nothing
    EXPECT_EQ(w.pending(), 1u);
    EXPECT_EQ(w.pending_acknowledged(), 1u);
    w.abandon_all([](std::uint64_t, std::string&&) {});
    EXPECT_EQ(w.pending_acknowledged(), 0u);
}

TEST(InFlightWindow, LongRunStaysConsistent) {
    InFlightWindow<int> w;
    std::uint64_t next_to_complete = 1;
    for (int i = 0; i < 10000; ++i) {
        w.add(i, i % 3 == 0);
        if (w.pending() > 50) {
            // Complete two at a time, the second one first.
            EXPECT_EQ(w.complete(next_to_complete + 1), static_cast<int>(next_to_complete));
            EXPECT_EQ(w.complete(next_to_complete), static_cast<int>(next_to_complete - 1));
            next_to_complete += 2;
        }
    }
    EXPECT_LE(w.pending(), 51u);
    // Every third one awaits an acknowledgement: ids 1, 4, 7, ... (i = id - 1).
    std::size_t acknowledged = 0;
    for (std::uint64_t id = next_to_complete; id <= 10000; ++id) acknowledged += (id - 1) % 3 == 0;
    EXPECT_EQ(w.pending_acknowledged(), acknowledged);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
