#include "eip2mqtt/adapters/udp/command_socket.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <optional>
#include <vector>

#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::adapters::udp {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr std::uint32_t loopback = 0x7F000001;

class CommandSocketTest : public ::testing::Test {
protected:
    CommandSocketTest() {
        socket_.start([this](std::span<const std::byte> datagram, const Endpoint& from) {
            received_.emplace_back(datagram.begin(), datagram.end());
            from_ = from;
        });
    }

    // Runs the loop until `count` datagrams came, for at most 5 s.
    void wait_for(std::size_t count) {
        const auto deadline = std::chrono::steady_clock::now() + 5s;
        while (received_.size() < count && std::chrono::steady_clock::now() < deadline) {
            io_.run_for(10ms);
        }
    }

    boost::asio::io_context io_;
    CommandSocket socket_{io_.get_executor(), "127.0.0.1", 0};
    std::vector<std::vector<std::byte>> received_;
    Endpoint from_;
};

TEST_F(CommandSocketTest, ReceivesWithTheSenderAndAnswersIt) {
    test::UdpClient client;
    const std::vector<std::byte> request(12, std::byte{9});
    client.send_to(socket_.local_port(), request);
    wait_for(1);
    ASSERT_EQ(received_.size(), 1u);
    EXPECT_EQ(received_[0], request);
    EXPECT_EQ(from_.address, loopback);
    EXPECT_EQ(from_.port, client.port());

    const std::vector<std::byte> response(76, std::byte{4});
    EXPECT_TRUE(socket_.send_to(response, from_));
    EXPECT_EQ(client.receive(2s), response);
    EXPECT_EQ(socket_.stats().received, 1u);
    EXPECT_EQ(socket_.stats().sent, 1u);
}

TEST_F(CommandSocketTest, AnOversizedDatagramArrivesLongerThanTheLargestPdu) {
    test::UdpClient client;
    client.send_to(socket_.local_port(), std::vector<std::byte>(3000, std::byte{1}));
    client.send_to(socket_.local_port(), std::vector<std::byte>(1400, std::byte{2}));
    wait_for(2);
    ASSERT_EQ(received_.size(), 2u);
    EXPECT_GT(received_[0].size(), core::command::max_pdu_size);
    EXPECT_EQ(received_[1].size(), core::command::max_pdu_size);
}

TEST_F(CommandSocketTest, ThePortIsOwned) {
    boost::asio::io_context other;
    EXPECT_THROW(CommandSocket(other.get_executor(), "127.0.0.1", socket_.local_port()),
                 std::system_error);
}

TEST(LocalSubnets, LoopbackHoldsItsOwnSubnet) {
    const auto subnets = local_subnets(loopback);
    ASSERT_FALSE(subnets.empty());
    EXPECT_TRUE(core::net::allowed(subnets, loopback));
    EXPECT_TRUE(core::net::allowed(local_subnets(0), loopback));
    // 198.51.100.1 (TEST-NET-2) is no interface's.
    EXPECT_TRUE(local_subnets(0xC6336401).empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::udp
