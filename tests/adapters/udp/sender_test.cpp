#include "eip2mqtt/adapters/udp/sender.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <vector>

#include "tests/support/udp_client.hpp"

namespace eip2mqtt::adapters::udp {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr std::uint32_t loopback = 0x7F000001;

std::vector<std::byte> bytes_of(std::size_t size, std::byte fill) {
    return std::vector<std::byte>(size, fill);
}

class SenderTest : public ::testing::Test {
protected:
    boost::asio::io_context io_;
    SenderOptions options_{.bind = "127.0.0.1"};
    Sender sender_{io_.get_executor(), options_};
};

TEST_F(SenderTest, BatchSendsEveryDatagramInOrder) {
    test::UdpClient a;
    test::UdpClient b;
    const auto one = bytes_of(40, std::byte{1});
    const auto two = bytes_of(33, std::byte{2});
    const auto three = bytes_of(1432, std::byte{3});
    const std::vector<OutgoingDatagram> batch{
        {one, {loopback, a.port()}}, {two, {loopback, b.port()}}, {three, {loopback, a.port()}}};
    std::vector<bool> sent;
    EXPECT_EQ(sender_.send_batch(batch, sent), 3u);
    EXPECT_EQ(sent, (std::vector<bool>{true, true, true}));
    EXPECT_EQ(sender_.stats().sent, 3u);
    EXPECT_EQ(sender_.stats().errors, 0u);
    EXPECT_EQ(a.receive(2s), one);
    EXPECT_EQ(a.receive(2s), three);
    EXPECT_EQ(b.receive(2s), two);
}

TEST_F(SenderTest, RefusedDatagramIsCountedAndTheRestStillLeave) {
    test::UdpClient a;
    const auto first = bytes_of(40, std::byte{1});
    const auto too_big = bytes_of(70000, std::byte{2});  // over UDP's 65,507: EMSGSIZE
    const auto last = bytes_of(41, std::byte{3});
    const std::vector<OutgoingDatagram> batch{{first, {loopback, a.port()}},
                                              {too_big, {loopback, a.port()}},
                                              {last, {loopback, a.port()}}};
    std::vector<bool> sent;
    EXPECT_EQ(sender_.send_batch(batch, sent), 2u);
    EXPECT_EQ(sent, (std::vector<bool>{true, false, true}));
    EXPECT_EQ(sender_.stats().sent, 2u);
    EXPECT_EQ(sender_.stats().errors, 1u);
    EXPECT_EQ(a.receive(2s), first);
    EXPECT_EQ(a.receive(2s), last);
}

TEST_F(SenderTest, RefusedFirstAndLastDatagrams) {
    test::UdpClient a;
    const auto bad = bytes_of(70000, std::byte{9});
    const auto good = bytes_of(40, std::byte{1});
    const std::vector<OutgoingDatagram> batch{
        {bad, {loopback, a.port()}}, {good, {loopback, a.port()}}, {bad, {loopback, a.port()}}};
    std::vector<bool> sent;
    EXPECT_EQ(sender_.send_batch(batch, sent), 1u);
    EXPECT_EQ(sent, (std::vector<bool>{false, true, false}));
    EXPECT_EQ(sender_.stats().errors, 2u);
    EXPECT_EQ(a.receive(2s), good);
}

TEST_F(SenderTest, EqualDatagramsToOneDestinationArriveSeparatelyAndInOrder) {
    // 150 datagrams of one size to `a` (more than one GSO message holds), interleaved with 3
    // of another size to `b`: each arrives as its own datagram, with its own bytes.
    test::UdpClient a;
    test::UdpClient b;
    std::vector<std::vector<std::byte>> to_a;
    std::vector<std::vector<std::byte>> to_b;
    for (int i = 0; i < 150; ++i) to_a.push_back(bytes_of(76, static_cast<std::byte>(i)));
    for (int i = 0; i < 3; ++i) to_b.push_back(bytes_of(33, static_cast<std::byte>(200 + i)));
    std::vector<OutgoingDatagram> batch;
    for (std::size_t i = 0; i < to_a.size(); ++i) {
        batch.push_back({to_a[i], {loopback, a.port()}});
        if (i % 50 == 0) batch.push_back({to_b[i / 50], {loopback, b.port()}});
    }
    std::vector<bool> sent;
    EXPECT_EQ(sender_.send_batch(batch, sent), 153u);
    EXPECT_EQ(sent, std::vector<bool>(153, true));
    EXPECT_EQ(sender_.stats().sent, 153u);
    for (const auto& expected : to_a) EXPECT_EQ(a.receive(2s), expected);
    for (const auto& expected : to_b) EXPECT_EQ(b.receive(2s), expected);
    EXPECT_FALSE(a.receive(100ms));  // nothing more: no datagram merged or split wrongly
}

TEST_F(SenderTest, EmptyBatchSendsNothing) {
    std::vector<bool> sent{true};
    EXPECT_EQ(sender_.send_batch({}, sent), 0u);
    EXPECT_TRUE(sent.empty());
    EXPECT_EQ(sender_.stats().sent + sender_.stats().errors, 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::udp
