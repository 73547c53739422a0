#include "adapters/mqtt/detail/tcp_nodelay.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

/// A connected loopback TCP pair: a listener, the client end and the accepted end.
struct LoopbackPair {
    LoopbackPair() {
        listener = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        EXPECT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
        EXPECT_EQ(::listen(listener, 1), 0);
        socklen_t len = sizeof address;
        ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &len);
        port = ntohs(address.sin_port);
        client = ::socket(AF_INET, SOCK_STREAM, 0);
        EXPECT_EQ(::connect(client, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
        accepted = ::accept(listener, nullptr, nullptr);
    }
    ~LoopbackPair() {
        ::close(accepted);
        ::close(client);
        ::close(listener);
    }
    int listener = -1;
    int client = -1;
    int accepted = -1;
    std::uint16_t port = 0;
};

bool nodelay(int fd) {
    int value = 0;
    socklen_t len = sizeof value;
    EXPECT_EQ(::getsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &value, &len), 0);
    return value != 0;
}

TEST(TcpNodelay, FindsOnlyTheSocketsConnectedToTheBroker) {
    LoopbackPair broker;
    LoopbackPair other;
    const auto fds = sockets_connected_to("127.0.0.1", broker.port);
    EXPECT_EQ(fds, std::vector<int>{broker.client});
    EXPECT_TRUE(sockets_connected_to("127.0.0.1", 1).empty());
}

TEST(TcpNodelay, SwitchIsOnWhileIdleAndOffOnlyWhileBacklogged) {
    LoopbackPair broker;
    ASSERT_FALSE(nodelay(broker.client));
    NagleSwitch nagle;
    nagle.attach(sockets_connected_to("127.0.0.1", broker.port));
    EXPECT_TRUE(nodelay(broker.client));
    nagle.set_backlogged(true);
    EXPECT_FALSE(nodelay(broker.client));
    nagle.set_backlogged(true);
    EXPECT_FALSE(nodelay(broker.client));
    nagle.set_backlogged(false);
    EXPECT_TRUE(nodelay(broker.client));

    // After a loss the sockets are forgotten: nothing is switched any more.
    nagle.detach();
    nagle.set_backlogged(true);
    EXPECT_TRUE(nodelay(broker.client));

    // A new connection starts idle (TCP_NODELAY on) whatever the state before.
    nagle.attach({broker.client});
    EXPECT_TRUE(nodelay(broker.client));
    nagle.set_backlogged(true);
    EXPECT_FALSE(nodelay(broker.client));
}

TEST(TcpNodelay, RefusedOnAClosedDescriptor) {
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    ::close(fd);
    EXPECT_FALSE(set_tcp_nodelay(fd, true));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
