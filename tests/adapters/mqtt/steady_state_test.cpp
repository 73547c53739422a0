// Issue #6: once warm, a publication's path through the MQTT adapter's own structures allocates
// nothing (Paho's copies are Paho's). Counted with a replaced operator new, on this thread.

#include <gtest/gtest.h>

#include <array>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "adapters/mqtt/detail/in_flight_window.hpp"
#include "adapters/mqtt/detail/outbox.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "tests/support/count_allocations.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using test::allocations_during;

constexpr std::size_t kTopics = 50;

std::vector<std::string> long_topics() {
    std::vector<std::string> topics;
    for (std::size_t i = 0; i < kTopics; ++i) {
        topics.push_back("acme/blumenau/turbine1/e1/TAG_" + std::to_string(i));
    }
    return topics;
}

const std::array<std::string, 2> payloads{
    R"({"value":1234,"timestamp":1732291200000,"quality":"good"})",
    R"({"value":-98765,"timestamp":1732291200010,"quality":"good"})"};

TEST(SteadyState, OutboxWindowAndSparesCycleWithoutAllocating) {
    // The client's cycle, on one thread, with its own parts: fill a message, push it to the
    // Outbox (a spare comes back when it is queued whole), take it into the in-flight window,
    // complete it, recycle it as a spare.
    const auto topics = long_topics();
    detail::Outbox outbox(1000, 1000);
    detail::InFlightWindow<Message> window;
    std::array<std::uint64_t, 2 * kTopics> ids{};
    Message message;
    auto publish = [&](std::size_t topic, std::size_t value) {
        message.topic.assign(topics[topic]);
        message.payload.assign(payloads[value % 2]);
        message.qos = 1;
        outbox.push(message);
    };
    auto rounds = [&] {
        for (std::size_t round = 0; round < 20; ++round) {
            for (std::size_t i = 0; i < kTopics; ++i) publish(i, round);
            for (std::size_t i = 0; i < kTopics; i += 2) publish(i, round + 1);  // coalesce
            std::size_t sent = 0;
            Message next;
            while (outbox.take_next(next)) ids[sent++] = window.add(std::move(next), true);
            for (std::size_t i = 0; i < sent; ++i) {
                outbox.recycle(std::move(*window.complete(ids[i])), 4 * kTopics);
            }
        }
    };
    rounds();  // warm: buffers, ring slots, index nodes and buckets reach their sizes
    EXPECT_EQ(allocations_during(rounds), 0u);
    EXPECT_EQ(outbox.tags().coalesced(), 2 * 20 * kTopics / 2);
}

TEST(SteadyState, ClientPublishAllocatesNothingOnceItsTopicsAreQueued) {
    // Not connected (nothing listens on the port): publications wait in the queue, and a newer
    // value of a queued topic gives back the buffers of the one it replaces.
    boost::asio::io_context io;
    ClientOptions options;
    options.urls = {"tcp://127.0.0.1:1"};
    Client client(io.get_executor(), options);
    const auto topics = long_topics();
    Message message;
    auto publish_all = [&](std::size_t value) {
        for (const auto& topic : topics) {
            message.topic.assign(topic);
            message.payload.assign(payloads[value % 2]);
            message.qos = 1;
            client.publish(std::move(message));
        }
    };
    // Warm: the buffers that circulate grow until each fits the longer payload.
    for (std::size_t value = 0; value < 4; ++value) publish_all(value);
    EXPECT_EQ(allocations_during([&] {
                  for (std::size_t value = 4; value < 14; ++value) publish_all(value);
              }),
              0u);
    EXPECT_EQ(client.stats().queued, kTopics);
    EXPECT_EQ(client.stats().coalesced, 13 * kTopics);
    client.stop(std::chrono::milliseconds(0));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
