#include "tests/support/segment_capture.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cstring>

namespace eip2mqtt::test {

SegmentCapture::SegmentCapture(int fd, std::chrono::system_clock::time_point epoch)
    : fd_(fd), epoch_(epoch) {
    const int on = 1;
    ::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    thread_ = std::thread([this] { run(); });
}

SegmentCapture::~SegmentCapture() {
    stop();
    ::close(fd_);
}

void SegmentCapture::stop() {
    {
        const std::lock_guard lock(mutex_);
        stop_ = true;
    }
    if (thread_.joinable()) thread_.join();
}

std::vector<SegmentCapture::Datagram> SegmentCapture::datagrams() const {
    const std::lock_guard lock(mutex_);
    return datagrams_;
}

void SegmentCapture::run() {
    std::array<std::byte, 2048> buffer;
    std::array<char, CMSG_SPACE(sizeof(timespec))> control;
    for (;;) {
        {
            const std::lock_guard lock(mutex_);
            if (stop_) return;
        }
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, 20) <= 0) continue;
        sockaddr_in from{};
        iovec io{buffer.data(), buffer.size()};
        msghdr message{};
        message.msg_name = &from;
        message.msg_namelen = sizeof from;
        message.msg_iov = &io;
        message.msg_iovlen = 1;
        message.msg_control = control.data();
        message.msg_controllen = control.size();
        const auto n = ::recvmsg(fd_, &message, MSG_DONTWAIT);
        if (n < 0) continue;
        auto arrived = std::chrono::system_clock::now();
        for (auto* c = CMSG_FIRSTHDR(&message); c != nullptr; c = CMSG_NXTHDR(&message, c)) {
            if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_TIMESTAMPNS) continue;
            timespec t{};
            std::memcpy(&t, CMSG_DATA(c), sizeof t);
            arrived = std::chrono::system_clock::time_point(
                std::chrono::duration_cast<std::chrono::system_clock::duration>(
                    std::chrono::seconds(t.tv_sec) + std::chrono::nanoseconds(t.tv_nsec)));
        }
        std::array<char, INET_ADDRSTRLEN> source{};
        ::inet_ntop(AF_INET, &from.sin_addr, source.data(), source.size());
        const std::lock_guard lock(mutex_);
        datagrams_.push_back(
            {source.data(), std::chrono::duration_cast<std::chrono::milliseconds>(arrived - epoch_),
             std::vector<std::byte>(buffer.begin(), buffer.begin() + n)});
    }
}

}  // namespace eip2mqtt::test
