#include "tests/support/scripted_broker.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>

namespace eip2mqtt::test {
namespace {

/// Reads exactly `size` bytes within `timeout_ms`; false on timeout, close or error.
bool read_exactly(int fd, std::uint8_t* into, std::size_t size, int timeout_ms) {
    std::size_t have = 0;
    while (have < size) {
        pollfd ready{fd, POLLIN, 0};
        if (::poll(&ready, 1, timeout_ms) <= 0) return false;
        const auto n = ::recv(fd, into + have, size - have, 0);
        if (n <= 0) return false;
        have += static_cast<std::size_t>(n);
    }
    return true;
}

/// Reads one MQTT packet (MQTT 5 §2.1: a fixed header byte, a variable-length remaining length,
/// then that many bytes); its bytes after the fixed header, or empty on failure.
std::vector<std::uint8_t> read_packet(int fd) {
    constexpr int timeout_ms = 5000;
    std::uint8_t byte = 0;
    if (!read_exactly(fd, &byte, 1, timeout_ms)) return {};
    std::size_t remaining = 0;
    for (int shift = 0; shift <= 21; shift += 7) {
        if (!read_exactly(fd, &byte, 1, timeout_ms)) return {};
        remaining |= static_cast<std::size_t>(byte & 0x7F) << shift;
        if ((byte & 0x80) == 0) break;
    }
    std::vector<std::uint8_t> body(remaining);
    if (remaining > 0 && !read_exactly(fd, body.data(), remaining, timeout_ms)) return {};
    return body.empty() ? std::vector<std::uint8_t>{0} : body;
}

void send_all(int fd, const std::vector<std::uint8_t>& bytes) {
    if (!bytes.empty()) ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
}

/// Closes our side only and reads until the client closes (2 s at most): closing with the
/// client's packets unread would send a reset, which may discard what we sent before it.
void close_after_client(int fd) {
    ::shutdown(fd, SHUT_WR);
    std::uint8_t sink[512];
    for (int i = 0; i < 20; ++i) {
        pollfd ready{fd, POLLIN, 0};
        if (::poll(&ready, 1, 100) > 0 && ::recv(fd, sink, sizeof sink, 0) <= 0) return;
    }
}

}  // namespace

ScriptedBroker::ScriptedBroker(std::vector<std::uint8_t> on_connect,
                               std::vector<std::uint8_t> after_next_packet)
    : on_connect_(std::move(on_connect)), after_next_packet_(std::move(after_next_packet)) {
    listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(listener_, reinterpret_cast<sockaddr*>(&at), sizeof at) != 0 ||
        ::listen(listener_, 16) != 0) {
        ADD_FAILURE() << "the scripted broker cannot listen";
        return;
    }
    socklen_t length = sizeof at;
    ::getsockname(listener_, reinterpret_cast<sockaddr*>(&at), &length);
    port_ = ntohs(at.sin_port);
    thread_ = std::thread([this] { serve(); });
}

ScriptedBroker::~ScriptedBroker() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    ::close(listener_);
}

void ScriptedBroker::serve() {
    while (!stop_) {
        // Wakes up every 100 ms to see whether the test is over.
        pollfd ready{listener_, POLLIN, 0};
        if (::poll(&ready, 1, 100) <= 0) continue;
        const int connection = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
        if (connection < 0) continue;
        ++connections_;
        play(connection);
        ::close(connection);
    }
}

void ScriptedBroker::play(int connection) {
    const auto connect = read_packet(connection);
    // CONNECT's variable header: protocol name (2-byte length, "MQTT"), then the level.
    if (connect.size() < 7) return;
    protocol_level_ = connect[6];
    if (on_connect_.empty()) return;  // closed on the CONNECT, as RabbitMQ 3.10 does on MQTT 5
    send_all(connection, on_connect_);
    if (!after_next_packet_.empty() && !read_packet(connection).empty()) {
        send_all(connection, after_next_packet_);
    }
    close_after_client(connection);
}

}  // namespace eip2mqtt::test
