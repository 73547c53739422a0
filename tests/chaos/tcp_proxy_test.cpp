// TcpProxy's run-time faults (tests/support/tcp_proxy.hpp), per direction: a delay holds what
// passes at least that long, a stall holds it until resumed, a cut throws it away without a
// word to either end. A client and a server of the test's own on loopback.

#include "tests/support/tcp_proxy.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "tests/support/loopback.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;
using D = TcpProxy::Direction;

/// What arrives on `fd` within `wait` (empty: nothing).
std::string receive(int fd, std::chrono::milliseconds wait) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) return "";
    char buffer[256];
    const auto n = ::recv(fd, buffer, sizeof buffer, 0);
    return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : "";
}

void send_text(int fd, const std::string& text) {
    ASSERT_EQ(::send(fd, text.data(), text.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(text.size()));
}

class TcpProxyFaults : public ::testing::Test {
protected:
    void SetUp() override {
        listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
        auto address = loopback(0);
        socklen_t length = sizeof address;
        ASSERT_EQ(::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
        ASSERT_EQ(::listen(listener_, 4), 0);
        ASSERT_EQ(::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length), 0);
        proxy_ = std::make_unique<TcpProxy>(ntohs(address.sin_port));
        client_ = ::socket(AF_INET, SOCK_STREAM, 0);
        const auto to = loopback(proxy_->port());
        ASSERT_EQ(::connect(client_, reinterpret_cast<const sockaddr*>(&to), sizeof to), 0);
        server_ = ::accept(listener_, nullptr, nullptr);
        ASSERT_GE(server_, 0);
    }
    void TearDown() override {
        proxy_.reset();
        for (const int fd : {client_, server_, listener_}) {
            if (fd >= 0) ::close(fd);
        }
    }
    int listener_ = -1;
    int client_ = -1;
    int server_ = -1;
    std::unique_ptr<TcpProxy> proxy_;
};

TEST_F(TcpProxyFaults, ADelayHoldsWhatPassesThatLongInOneDirectionOnly) {
    proxy_->set_delay(D::to_server, 400ms);
    send_text(client_, "late");
    EXPECT_EQ(receive(server_, 200ms), "");  // the delay is a floor, whatever the load
    EXPECT_EQ(receive(server_, 10s), "late");
    send_text(server_, "back");
    EXPECT_EQ(receive(client_, 10s), "back");
}

TEST_F(TcpProxyFaults, AStallHoldsUntilResumedACutThrowsAway) {
    proxy_->set_mode(D::to_server, TcpProxy::Mode::stall);
    send_text(client_, "held");
    EXPECT_EQ(receive(server_, 200ms), "");
    proxy_->set_mode(D::to_server, TcpProxy::Mode::pass);
    EXPECT_EQ(receive(server_, 10s), "held");

    proxy_->set_mode(D::to_client, TcpProxy::Mode::cut);
    send_text(server_, "lost");
    EXPECT_EQ(receive(client_, 300ms), "");
    // Neither end heard of the cut: the other direction still passes.
    send_text(client_, "still");
    EXPECT_EQ(receive(server_, 10s), "still");
    proxy_->set_mode(D::to_client, TcpProxy::Mode::pass);
    send_text(server_, "after");
    EXPECT_EQ(receive(client_, 10s), "after");  // and what the cut took never comes
}

TEST_F(TcpProxyFaults, StallAndResumeHoldBothDirections) {
    proxy_->stall();
    send_text(client_, "up");
    send_text(server_, "down");
    EXPECT_EQ(receive(server_, 200ms), "");
    EXPECT_EQ(receive(client_, 10ms), "");
    proxy_->resume();
    EXPECT_EQ(receive(server_, 10s), "up");
    EXPECT_EQ(receive(client_, 10s), "down");
}

}  // namespace
}  // namespace eip2mqtt::test
