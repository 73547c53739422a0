// Receiver: the gateway's port is its own. No other socket can bind it beside the gateway
// (Linux would hand that socket some of the unicast datagrams), a second receiver on it is
// refused with the holder named, a multicast group stays shareable with other consumers, and what
// waits unread can be taken without the loop (before timeouts are judged).

#include "eip2mqtt/adapters/udp/receiver.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <net/if.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "eip2mqtt/adapters/udp/sender.hpp"
#include "tests/support/igmp.hpp"

namespace eip2mqtt::adapters::udp {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// errno of binding a fresh UDP socket with SO_REUSEADDR and SO_REUSEPORT (the most sharing a
/// program can ask for) to `address`:`port`; 0 when the bind succeeded.
int bind_error(const char* address, std::uint16_t port, int* fd_out = nullptr) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    setsockopt(fd, SOL_SOCKET, SO_REUSEPORT, &on, sizeof on);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_port = htons(port);
    inet_pton(AF_INET, address, &at.sin_addr);
    const int result = ::bind(fd, reinterpret_cast<sockaddr*>(&at), sizeof at) == 0 ? 0 : errno;
    if (fd_out != nullptr && result == 0) {
        *fd_out = fd;
    } else {
        ::close(fd);
    }
    return result;
}

/// Datagrams waiting on `fd`, read without blocking.
int pending(int fd) {
    int count = 0;
    std::byte buffer[64];
    while (::recv(fd, buffer, sizeof buffer, MSG_DONTWAIT) >= 0) ++count;
    return count;
}

TEST(Receiver, NoOtherSocketCanBindItsPort) {
    boost::asio::io_context io;
    Receiver receiver(io.get_executor(), ReceiverOptions{.bind = "127.0.0.1", .port = 0});
    const auto port = receiver.local_port();
    EXPECT_EQ(bind_error("127.0.0.1", port), EADDRINUSE);
    EXPECT_EQ(bind_error("0.0.0.0", port), EADDRINUSE);

    Receiver wildcard(io.get_executor(), ReceiverOptions{.bind = "0.0.0.0", .port = 0});
    for (const auto* address : {"0.0.0.0", "127.0.0.1", "127.0.0.2", "224.0.7.1"}) {
        EXPECT_EQ(bind_error(address, wildcard.local_port()), EADDRINUSE) << address;
    }
}

TEST(Receiver, ASecondReceiverOnThePortIsRefusedWithTheHolderNamed) {
    boost::asio::io_context io;
    Receiver first(io.get_executor(), ReceiverOptions{.bind = "0.0.0.0", .port = 0});
    const auto port = first.local_port();
    try {
        Receiver second(io.get_executor(), ReceiverOptions{.bind = "127.0.0.1", .port = port});
        FAIL() << "a second receiver bound port " << port;
    } catch (const std::system_error& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.code(), std::errc::address_in_use) << what;
        EXPECT_NE(what.find("cannot bind UDP 127.0.0.1:" + std::to_string(port)), std::string::npos)
            << what;
        EXPECT_NE(what.find("held by process " + std::to_string(::getpid()) + " ("),
                  std::string::npos)
            << what;
    }
}

TEST(Receiver, ReadPendingTakesWhatWaitsWithoutTheLoopRunning) {
    boost::asio::io_context io;  // never run: a loop busy elsewhere
    Receiver receiver(io.get_executor(), ReceiverOptions{.bind = "127.0.0.1", .port = 0});
    std::vector<std::size_t> lengths;
    receiver.start([&](std::span<const std::byte> datagram, const Endpoint&, bool) {
        lengths.push_back(datagram.size());
    });
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(receiver.local_port());
    inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
    const std::byte datagram[3]{};
    for (int i = 0; i < 2; ++i) {
        ASSERT_EQ(::sendto(fd, datagram, sizeof datagram - static_cast<std::size_t>(i), 0,
                           reinterpret_cast<const sockaddr*>(&to), sizeof to),
                  static_cast<ssize_t>(sizeof datagram) - i);
    }
    ::close(fd);
    // Loopback has queued them once sendto returned, on every kernel we know; bounded all the
    // same.
    for (int i = 0; i < 1000 && lengths.size() < 2; ++i) {
        receiver.read_pending();
        if (lengths.size() < 2) std::this_thread::sleep_for(1ms);
    }
    EXPECT_EQ(lengths, (std::vector<std::size_t>{3, 2}));
    EXPECT_EQ(receiver.stats().datagrams, 2u);
    receiver.read_pending();  // nothing more: nothing handed on twice
    EXPECT_EQ(lengths.size(), 2u);
}

/// In a network namespace of its own (where loopback may carry multicast without touching the
/// host's): a gateway bound to 127.0.0.1 with a group, and a neighbour consuming the same
/// group on this host. Runs on a thread of its own, since a namespace is a thread's.
struct GroupOutcome {
    bool isolated = false;  ///< false: no namespace (not root); the test is skipped
    int thief_bind_error = 0;
    int neighbour_bind_error = -1;
    int receiver_datagrams = 0;
    int neighbour_datagrams = 0;
};

/// Brings loopback up with multicast in the calling thread's (new) namespace.
bool loopback_with_multicast() {
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ifreq request{};
    std::strncpy(request.ifr_name, "lo", IFNAMSIZ - 1);
    bool ok = ::ioctl(fd, SIOCGIFFLAGS, &request) == 0;
    request.ifr_flags = static_cast<short>(request.ifr_flags | IFF_UP | IFF_MULTICAST);
    ok = ok && ::ioctl(fd, SIOCSIFFLAGS, &request) == 0;
    ::close(fd);
    return ok;
}

GroupOutcome share_a_group() {
    GroupOutcome outcome;
    if (::unshare(CLONE_NEWNET) != 0 || !loopback_with_multicast()) return outcome;
    outcome.isolated = true;
    boost::asio::io_context io;
    const MulticastMembership group{"239.1.2.3", "127.0.0.1"};
    Receiver receiver(io.get_executor(),
                      ReceiverOptions{.bind = "127.0.0.1", .port = 0, .multicast = {group}});
    const auto port = receiver.local_port();
    outcome.thief_bind_error = bind_error("127.0.0.1", port);
    int neighbour = -1;
    outcome.neighbour_bind_error = bind_error("239.1.2.3", port, &neighbour);
    if (neighbour >= 0) join_group(neighbour, group);

    receiver.start([&](std::span<const std::byte>, const Endpoint&, bool) {
        if (++outcome.receiver_datagrams == 2) io.stop();
    });
    Sender sender(io.get_executor(),
                  SenderOptions{.bind = "127.0.0.1", .multicast_interface = "127.0.0.1"});
    const std::vector<std::byte> bytes(4, std::byte{1});
    sender.send_to(bytes, {0xEF010203, port});  // 239.1.2.3
    sender.send_to(bytes, {0x7F000001, port});
    io.run_for(10s);
    if (neighbour >= 0) {
        outcome.neighbour_datagrams = pending(neighbour);
        ::close(neighbour);
    }
    return outcome;
}

TEST(Receiver, AMulticastGroupIsSharedButTheUnicastAddressIsNot) {
    GroupOutcome outcome;
    std::thread([&] { outcome = share_a_group(); }).join();
    if (!outcome.isolated) GTEST_SKIP() << "no network namespace of our own (needs root)";
    EXPECT_EQ(outcome.thief_bind_error, EADDRINUSE);
    EXPECT_EQ(outcome.neighbour_bind_error, 0);
    EXPECT_EQ(outcome.receiver_datagrams, 2);   // the group's datagram and the unicast one
    EXPECT_EQ(outcome.neighbour_datagrams, 1);  // its own copy of the group's
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::udp
