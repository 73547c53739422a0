#include "tests/support/http_get.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>

#include "tests/support/loopback.hpp"

namespace eip2mqtt::test {

std::string http_get(std::uint16_t port, const std::string& path) {
    return http_request(port, "GET", path);
}

namespace {

/// A socket connected to 127.0.0.1:`port` that sent `method path` (HTTP/1.0), reads timing out
/// after 5 s; -1 when it could not connect.
int send_request(std::uint16_t port, const std::string& method, const std::string& path,
                 const std::string& headers = "") {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) return -1;
    timeval timeout{5, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    const auto address = loopback(port);
    const std::string request =
        method + " " + path + " HTTP/1.0\r\nHost: localhost\r\n" + headers + "\r\n";
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
        ::send(fd, request.data(), request.size(), 0) != static_cast<ssize_t>(request.size())) {
        ::close(fd);
        return -1;
    }
    return fd;
}

/// `text` with each CR and LF written as printf's %b reads them back.
std::string escaped(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '\r') {
            out += "\\r";
        } else if (c == '\n') {
            out += "\\n";
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace

std::string http_request(std::uint16_t port, const std::string& method, const std::string& path,
                         const std::string& headers) {
    const int fd = send_request(port, method, path, headers);
    if (fd < 0) return {};
    std::string response;
    char buffer[4096];
    for (;;) {
        const auto n = ::recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        response.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return response;
}

std::string http_read_until(std::uint16_t port, const std::string& path, const std::string& needle,
                            int timeout_ms) {
    const int fd = send_request(port, "GET", path);
    if (fd < 0) return {};
    std::string response;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (response.find(needle) == std::string::npos) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        pollfd entry{fd, POLLIN, 0};
        if (left.count() <= 0 || ::poll(&entry, 1, static_cast<int>(left.count())) <= 0) break;
        char buffer[4096];
        const auto n = ::recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        response.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return response;
}

std::pair<std::string, std::string> status_and_body(const std::string& response) {
    const auto space = response.find(' ');
    const auto body = response.find("\r\n\r\n");
    if (space == std::string::npos || body == std::string::npos) return {"", response};
    return {response.substr(space + 1, 3), response.substr(body + 4)};
}

SilentClient::SilentClient(std::uint16_t port, const std::string& sent)
    : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    if (fd_ < 0) return;
    const auto address = loopback(port);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
    if (connected_ && !sent.empty()) ::send(fd_, sent.data(), sent.size(), 0);
}

SilentClient::~SilentClient() {
    if (fd_ >= 0) ::close(fd_);
}

bool SilentClient::closed_by_server(int timeout_ms) const {
    if (!connected_) return false;
    pollfd entry{fd_, POLLIN, 0};
    if (::poll(&entry, 1, timeout_ms) <= 0) return false;
    char buffer[256];
    // An answer (civetweb's 408, if any) and then the end; 0 is the end.
    for (;;) {
        const auto n = ::recv(fd_, buffer, sizeof buffer, MSG_DONTWAIT);
        if (n == 0) return true;
        if (n < 0) return errno != EAGAIN && errno != EWOULDBLOCK;
        if (::poll(&entry, 1, timeout_ms) <= 0) return false;
    }
}

std::pair<bool, std::string> https_get(std::uint16_t port, const std::string& path,
                                       const std::string& ca_file, const std::string& headers) {
    const std::string request = "GET " + path + " HTTP/1.0\r\nHost: localhost\r\n" + headers;
    // printf's %b expands the \r\n escapes; the request is ours, without a quote in it.
    const std::string command = "printf '%b\\r\\n' '" + escaped(request) +
                                "' | timeout 10 openssl s_client -quiet -verify_return_error "
                                "-servername localhost -CAfile '" +
                                ca_file + "' -connect 127.0.0.1:" + std::to_string(port) +
                                " 2>/dev/null";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return {false, ""};
    std::string out;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
        out.append(buffer, n);
    const int status = ::pclose(pipe);
    return {status == 0 && !out.empty(), out};
}

}  // namespace eip2mqtt::test
