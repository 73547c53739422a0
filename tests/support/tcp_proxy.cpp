#include "tests/support/tcp_proxy.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <stdexcept>
#include <string>

#include "tests/support/loopback.hpp"

namespace eip2mqtt::test {
namespace {

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

TcpProxy::TcpProxy(std::uint16_t upstream_port, Tap tap)
    : upstream_port_(upstream_port), tap_(std::move(tap)) {
    listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    auto address = loopback(0);
    if (listener_ < 0 ||
        ::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::listen(listener_, 16) != 0) {
        if (listener_ >= 0) ::close(listener_);
        throw std::runtime_error("TcpProxy: cannot listen on loopback");
    }
    start();
}

TcpProxy::TcpProxy(std::uint16_t upstream_port, int listener)
    : listener_(listener), upstream_port_(upstream_port) {
    start();
}

void TcpProxy::start() {
    sockaddr_in address{};
    socklen_t length = sizeof address;
    if (::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
        ::close(listener_);
        throw std::runtime_error("TcpProxy: the listener has no address");
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
        // Stalled, nothing is watched: the poll only paces the checks of the flags. A stalled
        // direction's socket is not read: its data waits in the kernel.
        if (!stalled_) {
            const auto events = [&](Direction d) -> short {
                return modes_[index(d)] == Mode::stall ? 0 : POLLIN;
            };
            fds.push_back({listener_, POLLIN, 0});
            for (const auto& link : links_) {
                fds.push_back({link.client, events(Direction::to_server), 0});
                fds.push_back({link.server, events(Direction::to_client), 0});
            }
        }
        const int ready_count = ::poll(fds.data(), fds.size(), poll_timeout(Clock::now()));
        if (stalled_ || fds.empty()) continue;
        const std::size_t polled = links_.size();
        if (ready_count > 0 && (fds[0].revents & POLLIN)) accept_one();
        const auto ready = [&](std::size_t entry) {
            return ready_count > 0 && (fds[entry].revents & (POLLIN | POLLHUP | POLLERR)) != 0;
        };
        const auto now = Clock::now();
        std::vector<Link> open;
        for (std::size_t i = 0; i < links_.size(); ++i) {
            auto& link = links_[i];
            // A link accepted in this round has no poll entry yet: it is only flushed.
            const bool up =
                (i >= polled || ((!ready(1 + 2 * i) || read(link, Direction::to_server)) &&
                                 (!ready(2 + 2 * i) || read(link, Direction::to_client)))) &&
                flush(link, now);
            if (up) {
                open.push_back(std::move(link));
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
    links_.push_back({connections_++, client, server, {}});
}

bool TcpProxy::read(Link& link, Direction direction) {
    const auto mode = modes_[index(direction)].load();
    if (mode == Mode::stall) return true;
    const int from = direction == Direction::to_server ? link.client : link.server;
    std::vector<char> buffer(16384);
    const auto n = ::recv(from, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n == 0) {
        if (tap_) tap_(link.id, direction, {}, true);
        return false;
    }
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK;
    if (tap_)
        tap_(link.id, direction, std::string_view(buffer.data(), static_cast<std::size_t>(n)),
             false);
    if (mode == Mode::cut) return true;
    buffer.resize(static_cast<std::size_t>(n));
    const std::chrono::milliseconds delay(delays_ms_[index(direction)]);
    link.pending[index(direction)].push_back({Clock::now() + delay, std::move(buffer)});
    return true;
}

bool TcpProxy::flush(Link& link, Clock::time_point now) {
    for (const auto direction : {Direction::to_server, Direction::to_client}) {
        if (modes_[index(direction)] == Mode::stall) continue;
        const int to = direction == Direction::to_server ? link.server : link.client;
        // In order: a chunk read after a shorter delay was set waits for the ones before it.
        auto& queue = link.pending[index(direction)];
        while (!queue.empty() && queue.front().due <= now) {
            const auto& bytes = queue.front().bytes;
            if (!write_all(to, bytes.data(), bytes.size())) return false;
            queue.pop_front();
        }
    }
    return true;
}

int TcpProxy::poll_timeout(Clock::time_point now) const {
    auto wait = std::chrono::milliseconds(20);
    for (const auto& link : links_) {
        for (const auto& queue : link.pending) {
            if (queue.empty()) continue;
            const auto until =
                std::chrono::duration_cast<std::chrono::milliseconds>(queue.front().due - now);
            wait = std::clamp(until, std::chrono::milliseconds(0), wait);
        }
    }
    return static_cast<int>(wait.count());
}

}  // namespace eip2mqtt::test
