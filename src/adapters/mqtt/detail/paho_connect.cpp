// The process's connect() and usleep(): the C library's, and in Paho's named threads a connect
// in progress waited for and its socket read at once (paho_connect.hpp says why).

#include "adapters/mqtt/detail/paho_connect.hpp"

#include <dlfcn.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>

#include "adapters/mqtt/detail/broker_url.hpp"

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

using ConnectFunction = int (*)(int, const sockaddr*, socklen_t);

ConnectFunction libc_connect() {
    static const auto function = reinterpret_cast<ConnectFunction>(::dlsym(RTLD_NEXT, "connect"));
    return function;
}

/// The receive thread's wake-up; a flag, so that a socket added just before it sleeps counts.
struct SocketNotice {
    std::mutex mutex;
    std::condition_variable added;
    bool pending = false;
};

SocketNotice& socket_notice() {
    static SocketNotice notice;
    return notice;
}

/// One bit a port; read by every connect of the process, so without a lock.
std::array<std::atomic<std::uint64_t>, 65536 / 64>& tls_ports() {
    static std::array<std::atomic<std::uint64_t>, 65536 / 64> ports{};
    return ports;
}

std::uint16_t port_of(const sockaddr* address, socklen_t length) {
    if (address->sa_family == AF_INET && length >= sizeof(sockaddr_in)) {
        return ntohs(reinterpret_cast<const sockaddr_in*>(address)->sin_port);
    }
    if (address->sa_family == AF_INET6 && length >= sizeof(sockaddr_in6)) {
        return ntohs(reinterpret_cast<const sockaddr_in6*>(address)->sin6_port);
    }
    return 0;
}

}  // namespace

int finish_connect(int fd, std::chrono::milliseconds wait) {
    pollfd polled{fd, POLLOUT, 0};
    const int ready = ::poll(&polled, 1, static_cast<int>(wait.count()));
    if (ready != 1) {
        errno = EINPROGRESS;  // not yet (or interrupted): Paho's own path takes over
        return -1;
    }
    int error = 0;
    socklen_t size = sizeof error;
    if (::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &size) != 0) return -1;
    if (error != 0) {
        errno = error;
        return -1;
    }
    return 0;
}

bool in_paho_thread(const char* name) {
    char own[16] = {};
    return ::pthread_getname_np(::pthread_self(), own, sizeof own) == 0 &&
           std::strcmp(own, name) == 0;
}

void paho_socket_added() {
    auto& notice = socket_notice();
    {
        std::lock_guard lock(notice.mutex);
        notice.pending = true;
    }
    notice.added.notify_all();
}

bool sleep_until_paho_socket(std::chrono::microseconds limit) {
    auto& notice = socket_notice();
    std::unique_lock lock(notice.mutex);
    const bool woken = notice.added.wait_for(lock, limit, [&] { return notice.pending; });
    notice.pending = false;
    return woken;
}

void paho_tls_port(std::uint16_t port) {
    tls_ports()[port / 64].fetch_or(std::uint64_t{1} << (port % 64), std::memory_order_relaxed);
}

bool is_paho_tls_port(std::uint16_t port) {
    return (tls_ports()[port / 64].load(std::memory_order_relaxed) >> (port % 64)) & 1;
}

std::chrono::milliseconds paho_connects_at_once(const std::vector<std::string>& urls) {
    for (const auto& url : urls) {
        const auto endpoint = parse_broker_url(url);
        if (endpoint && endpoint->tls) paho_tls_port(endpoint->port);
    }
    return paho_connect_wait;
}

}  // namespace eip2mqtt::adapters::mqtt::detail

extern "C" int connect(int fd, const sockaddr* address, socklen_t length) {
    namespace detail = eip2mqtt::adapters::mqtt::detail;
    const auto function = detail::libc_connect();
    if (function == nullptr) {
        errno = ENOSYS;
        return -1;
    }
    int rc = function(fd, address, length);
    const int error = errno;
    if ((rc == 0 || error == EINPROGRESS) && detail::in_paho_thread("MQTTAsync_send") &&
        !detail::is_paho_tls_port(detail::port_of(address, length))) {
        if (rc != 0) rc = detail::finish_connect(fd, detail::paho_connect_wait);
        const int outcome = errno;
        if (rc == 0 || outcome == EINPROGRESS) detail::paho_socket_added();
        errno = outcome;
        return rc;
    }
    errno = error;
    return rc;
}

extern "C" int usleep(useconds_t microseconds) {
    namespace detail = eip2mqtt::adapters::mqtt::detail;
    if (detail::in_paho_thread("MQTTAsync_rcv")) {
        detail::sleep_until_paho_socket(std::chrono::microseconds(microseconds));
        return 0;
    }
    const timespec duration{static_cast<time_t>(microseconds / 1000000),
                            static_cast<long>(microseconds % 1000000) * 1000};
    return ::nanosleep(&duration, nullptr);
}
