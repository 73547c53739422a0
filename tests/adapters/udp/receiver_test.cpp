// Receiver: with ReceiverOptions::destinations, each datagram comes with the address it was
// sent to (IP_PKTINFO), which `sniff --yaml` reports as unicast, broadcast or multicast.

#include "eip2mqtt/adapters/udp/receiver.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <system_error>
#include <vector>

#include "eip2mqtt/adapters/udp/sender.hpp"
#include "tests/support/igmp.hpp"

namespace eip2mqtt::adapters::udp {
namespace {

using namespace std::chrono_literals;

struct Seen {
    std::vector<std::byte> bytes;
    std::uint32_t destination = 0;
};

/// Sends `datagrams` (each to its address) to a receiver bound to 0.0.0.0 and returns what it
/// handed on, waiting (bounded) until all of them came.
std::vector<Seen> receive(bool destinations,
                          const std::vector<std::pair<std::uint32_t, std::byte>>& datagrams) {
    boost::asio::io_context io;
    Receiver receiver(io.get_executor(),
                      ReceiverOptions{.bind = "0.0.0.0", .port = 0, .destinations = destinations});
    std::vector<Seen> seen;
    auto keep = [&](std::span<const std::byte> bytes, std::uint32_t destination) {
        seen.push_back({{bytes.begin(), bytes.end()}, destination});
        if (seen.size() == datagrams.size()) io.stop();
    };
    if (destinations) {
        receiver.start_with_destinations([&](std::span<const std::byte> bytes, const Endpoint&,
                                             std::uint32_t destination,
                                             bool) { keep(bytes, destination); });
    } else {
        receiver.start([&](std::span<const std::byte> bytes, const Endpoint&, bool) {
            keep(bytes, 0xFFFFFFFF);  // a marker: no destination was handed on
        });
    }
    Sender sender(io.get_executor(), SenderOptions{.bind = "127.0.0.1"});
    for (const auto& [address, fill] : datagrams) {
        const std::vector<std::byte> bytes(4, fill);
        EXPECT_TRUE(sender.send_to(bytes, {address, receiver.local_port()}));
    }
    io.run_for(10s);
    return seen;
}

TEST(Receiver, HandsOnEachDatagramsDestinationAddress) {
    // The whole of 127.0.0.0/8 is the loopback interface's: two destinations, one socket.
    const auto seen = receive(true, {{0x7F000001, std::byte{1}}, {0x7F000002, std::byte{2}}});
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0].bytes, std::vector<std::byte>(4, std::byte{1}));
    EXPECT_EQ(seen[0].destination, 0x7F000001u);
    EXPECT_EQ(seen[1].bytes, std::vector<std::byte>(4, std::byte{2}));
    EXPECT_EQ(seen[1].destination, 0x7F000002u);
}

TEST(Receiver, WithoutDestinationsThePlainHandlerRuns) {
    const auto seen = receive(false, {{0x7F000001, std::byte{7}}});
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].bytes, std::vector<std::byte>(4, std::byte{7}));
    EXPECT_EQ(seen[0].destination, 0xFFFFFFFFu);
}

TEST(Receiver, SetMulticastLeavesTheGroupsDroppedAndJoinsTheNewOnes) {
    const auto kept = test::test_multicast_group(11);
    const auto dropped = test::test_multicast_group(12);
    const auto added = test::test_multicast_group(13);
    boost::asio::io_context io;
    Receiver receiver(
        io.get_executor(),
        ReceiverOptions{
            .bind = "127.0.0.1", .port = 0, .multicast = {{kept, "lo"}, {dropped, "lo"}}});
    ASSERT_TRUE(test::igmp_joined("lo", kept));
    ASSERT_TRUE(test::igmp_joined("lo", dropped));

    receiver.set_multicast({{kept, "lo"}, {added, "lo"}});
    EXPECT_TRUE(test::igmp_joined("lo", kept));
    EXPECT_FALSE(test::igmp_joined("lo", dropped));
    EXPECT_TRUE(test::igmp_joined("lo", added));

    receiver.stop();
    EXPECT_FALSE(test::igmp_joined("lo", kept));
    EXPECT_FALSE(test::igmp_joined("lo", added));
}

TEST(Receiver, SetMulticastThatCannotJoinAGroupChangesNothing) {
    // All or nothing: a reload refused for its multicast groups leaves the running ones joined.
    const auto first = test::test_multicast_group(14);
    const auto second = test::test_multicast_group(15);
    const auto third = test::test_multicast_group(16);
    boost::asio::io_context io;
    Receiver receiver(
        io.get_executor(),
        ReceiverOptions{.bind = "127.0.0.1", .port = 0, .multicast = {{first, "lo"}}});
    EXPECT_THROW(receiver.set_multicast({{second, "lo"}, {third, "no-such-if0"}}),
                 std::system_error);
    EXPECT_TRUE(test::igmp_joined("lo", first));
    EXPECT_FALSE(test::igmp_joined("lo", second));

    // Still able to change: what it holds is what it had.
    receiver.set_multicast({{second, "lo"}});
    EXPECT_FALSE(test::igmp_joined("lo", first));
    EXPECT_TRUE(test::igmp_joined("lo", second));
}

}  // namespace
}  // namespace eip2mqtt::adapters::udp
