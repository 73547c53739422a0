#include "tests/support/free_port.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace eip2mqtt::test {
namespace {

/// Whether a socket of `type` can be bound to 127.0.0.1:`port` now (0: any; the port taken
/// is written back).
bool can_bind(int type, std::uint16_t& port) {
    const int fd = ::socket(AF_INET, type | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
    }
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(port);
    socklen_t len = sizeof addr;
    const bool bound = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
                       ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0;
    ::close(fd);
    if (bound) port = ntohs(addr.sin_port);
    return bound;
}

/// The lowest port the kernel numbers its own sockets from (ip_local_port_range).
std::uint16_t ephemeral_low() {
    std::ifstream range("/proc/sys/net/ipv4/ip_local_port_range");
    unsigned low = 0;
    return range >> low && low > 20000 && low <= 65535 ? static_cast<std::uint16_t>(low) : 32768;
}

std::uint16_t free_port(int type) {
    // Below the kernel's ephemeral range: a port it handed out and took back (bind to 0) may be
    // handed again to the next socket that connects or sends, of this test or another, before
    // the process the port is meant for binds it. A port the kernel never numbers itself is
    // only taken by a test that chose it too, which the bind below sees.
    static std::mt19937 pick(std::random_device{}() ^ static_cast<unsigned>(::getpid()));
    constexpr std::uint16_t lowest = 10000;
    const std::uint16_t below = ephemeral_low();
    for (int attempt = 0; attempt < 100; ++attempt) {
        auto port = static_cast<std::uint16_t>(lowest + pick() % (below - lowest));
        if (can_bind(type, port)) return port;
    }
    std::uint16_t any = 0;
    if (!can_bind(type, any))
        throw std::runtime_error(std::string("bind: ") + std::strerror(errno));
    return any;
}

}  // namespace

std::uint16_t free_tcp_port() { return free_port(SOCK_STREAM); }
std::uint16_t free_udp_port() { return free_port(SOCK_DGRAM); }

bool accepts_connections(std::uint16_t port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        return false;
    }
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = htons(port);
    const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    ::close(fd);
    return ok;
}

}  // namespace eip2mqtt::test
