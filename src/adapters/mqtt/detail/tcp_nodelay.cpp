#include "adapters/mqtt/detail/tcp_nodelay.hpp"

#include <arpa/inet.h>
#include <dirent.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

std::vector<sockaddr_storage> resolve(const std::string& host, std::uint16_t port) {
    std::vector<sockaddr_storage> out;
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* res = nullptr;
    const std::string service = std::to_string(port);
    if (::getaddrinfo(host.c_str(), service.c_str(), &hints, &res) != 0) {
        return out;
    }
    for (addrinfo* ai = res; ai != nullptr; ai = ai->ai_next) {
        sockaddr_storage ss{};
        std::memcpy(&ss, ai->ai_addr, ai->ai_addrlen);
        out.push_back(ss);
    }
    ::freeaddrinfo(res);
    return out;
}

bool same_endpoint(const sockaddr_storage& a, const sockaddr_storage& b) {
    if (a.ss_family != b.ss_family) {
        return false;
    }
    if (a.ss_family == AF_INET) {
        const auto& x = reinterpret_cast<const sockaddr_in&>(a);
        const auto& y = reinterpret_cast<const sockaddr_in&>(b);
        return x.sin_port == y.sin_port && x.sin_addr.s_addr == y.sin_addr.s_addr;
    }
    if (a.ss_family == AF_INET6) {
        const auto& x = reinterpret_cast<const sockaddr_in6&>(a);
        const auto& y = reinterpret_cast<const sockaddr_in6&>(b);
        return x.sin6_port == y.sin6_port &&
               std::memcmp(&x.sin6_addr, &y.sin6_addr, sizeof x.sin6_addr) == 0;
    }
    return false;
}

bool is_stream_socket(int fd) {
    int type = 0;
    socklen_t len = sizeof type;
    return ::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) == 0 && type == SOCK_STREAM;
}

}  // namespace

std::vector<int> sockets_connected_to(const std::string& host, std::uint16_t port) {
    std::vector<int> fds;
    const auto broker = resolve(host, port);
    if (broker.empty()) {
        return fds;
    }
    DIR* dir = ::opendir("/proc/self/fd");
    if (dir == nullptr) {
        return fds;
    }
    const int dir_fd = ::dirfd(dir);
    while (const dirent* entry = ::readdir(dir)) {
        char* end = nullptr;
        const long fd_long = std::strtol(entry->d_name, &end, 10);
        if (end == entry->d_name || *end != '\0' || fd_long == dir_fd) {
            continue;
        }
        const int fd = static_cast<int>(fd_long);
        if (!is_stream_socket(fd)) {
            continue;
        }
        sockaddr_storage peer{};
        socklen_t len = sizeof peer;
        if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &len) != 0 ||
            (peer.ss_family != AF_INET && peer.ss_family != AF_INET6)) {
            continue;
        }
        for (const auto& b : broker) {
            if (same_endpoint(peer, b)) {
                fds.push_back(fd);
                break;
            }
        }
    }
    ::closedir(dir);
    return fds;
}

bool set_tcp_nodelay(int fd, bool on) {
    const int value = on ? 1 : 0;
    return ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &value, sizeof value) == 0;
}

void NagleSwitch::attach(std::vector<int> fds) {
    std::lock_guard lock(mutex_);
    fds_ = std::move(fds);
    backlogged_ = false;
    wanted_backlogged_ = false;
    for (const int fd : fds_) {
        set_tcp_nodelay(fd, true);
    }
}

void NagleSwitch::detach() {
    std::lock_guard lock(mutex_);
    fds_.clear();
    backlogged_ = false;
    wanted_backlogged_ = false;
}

void NagleSwitch::set_backlogged(bool backlogged) {
    // The common case, no change, costs one relaxed load and no lock.
    if (wanted_backlogged_.load(std::memory_order_relaxed) == backlogged) {
        return;
    }
    std::lock_guard lock(mutex_);
    wanted_backlogged_ = backlogged;
    if (backlogged_ == backlogged) {
        return;
    }
    backlogged_ = backlogged;
    for (const int fd : fds_) {
        set_tcp_nodelay(fd, !backlogged);
    }
}

}  // namespace eip2mqtt::adapters::mqtt::detail
