#include "tests/support/tcp_proxy.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <stdexcept>
#include <string>

namespace eip2mqtt::test {
namespace {

sockaddr_in loopback(std::uint16_t port) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return address;
}

/// Writes all of `size` bytes (the other end reads as it can: a test's messages are small).
bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const auto n = ::send(fd, data, size, MSG_NOSIGNAL);
        if (n <= 0) return false;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

TcpProxy::TcpProxy(std::uint16_t upstream_port) : upstream_port_(upstream_port) {
    listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    auto address = loopback(0);
    socklen_t length = sizeof address;
    if (listener_ < 0 ||
        ::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::listen(listener_, 16) != 0 ||
        ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
        if (listener_ >= 0) ::close(listener_);
        throw std::runtime_error("TcpProxy: cannot listen on loopback");
    }
    port_ = ntohs(address.sin_port);
    thread_ = std::thread([this] { run(); });
}

TcpProxy::~TcpProxy() {
    stop_ = true;
    thread_.join();
    for (const auto& link : links_) {
        ::close(link.client);
        ::close(link.server);
    }
    ::close(listener_);
}

void TcpProxy::run() {
    std::vector<pollfd> fds;
    while (!stop_) {
        fds.clear();
        // Stalled, nothing is watched: the poll only paces the checks of the flags.
        if (!stalled_) {
            fds.push_back({listener_, POLLIN, 0});
            const short upstream = upstream_stalled_ ? 0 : POLLIN;
            for (const auto& link : links_) {
                fds.push_back({link.client, upstream, 0});
                fds.push_back({link.server, POLLIN, 0});
            }
        }
        if (::poll(fds.data(), fds.size(), 20) <= 0 || stalled_) continue;
        const std::size_t polled = links_.size();
        if (fds[0].revents & POLLIN) accept_one();
        const auto ready = [&](std::size_t entry) {
            return (fds[entry].revents & (POLLIN | POLLHUP | POLLERR)) != 0;
        };
        std::vector<Link> open;
        for (std::size_t i = 0; i < links_.size(); ++i) {
            const auto& link = links_[i];
            // A link accepted in this round has no poll entry yet: kept as it is.
            const bool up =
                i >= polled ||
                ((!ready(1 + 2 * i) || upstream_stalled_ || pass(link.client, link.server)) &&
                 (!ready(2 + 2 * i) || pass(link.server, link.client)));
            if (up) {
                open.push_back(link);
            } else {
                ::close(link.client);
                ::close(link.server);
            }
        }
        links_ = std::move(open);
    }
}

void TcpProxy::accept_one() {
    const int client = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) return;
    const int server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const auto address = loopback(upstream_port_);
    if (server < 0 ||
        ::connect(server, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        ::close(client);
        if (server >= 0) ::close(server);
        return;
    }
    // A peer that stops reading must not hold the proxy's thread (and the test's end) forever.
    const timeval timeout{1, 0};
    for (const int fd : {client, server}) {
        ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    }
    links_.push_back({client, server});
    ++connections_;
}

bool TcpProxy::pass(int from, int to) {
    std::array<char, 16384> buffer;
    const auto n = ::recv(from, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK;
    return write_all(to, buffer.data(), static_cast<std::size_t>(n));
}

}  // namespace eip2mqtt::test
