// udp_port_holders names the processes bound to a UDP port, for the message of a refused bind.

#include "eip2mqtt/adapters/udp/port_holders.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

namespace eip2mqtt::adapters::udp {
namespace EIP2MQTT_THIS_FILE {

/// A UDP socket bound to 127.0.0.1 on an ephemeral port, closed at the end of the scope.
struct BoundSocket {
    BoundSocket() {
        fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        sockaddr_in at{};
        at.sin_family = AF_INET;
        at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&at), sizeof at), 0);
        socklen_t length = sizeof at;
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&at), &length);
        port = ntohs(at.sin_port);
    }
    ~BoundSocket() { ::close(fd); }
    int fd = -1;
    std::uint16_t port = 0;
};

TEST(PortHolders, NamesTheProcessBoundToThePort) {
    BoundSocket socket;
    const auto holders = udp_port_holders(socket.port);
    EXPECT_EQ(holders.sockets, 1u);
    ASSERT_EQ(holders.processes.size(), 1u);
    EXPECT_EQ(holders.processes[0].pid, ::getpid());
    EXPECT_NE(holders.processes[0].command.find("adapter_tests"), std::string::npos)
        << holders.processes[0].command;
    EXPECT_EQ(describe_udp_port_holders(socket.port)
                  .rfind("held by process " + std::to_string(::getpid()) + " (", 0),
              0u)
        << describe_udp_port_holders(socket.port);
}

TEST(PortHolders, AFreePortHasNone) {
    std::uint16_t port = 0;
    {
        BoundSocket socket;
        port = socket.port;
    }
    EXPECT_EQ(udp_port_holders(port).sockets, 0u);
    EXPECT_TRUE(udp_port_holders(port).processes.empty());
    EXPECT_EQ(describe_udp_port_holders(port), "");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::udp
