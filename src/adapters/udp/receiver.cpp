#include "eip2mqtt/adapters/udp/receiver.hpp"

#include <arpa/inet.h>
#include <net/if.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/error.hpp>
#include <boost/asio/ip/address_v4.hpp>
#include <cerrno>
#include <cstring>
#include <string_view>
#include <system_error>

namespace eip2mqtt::adapters::udp {
namespace {

// Room for any datagram EIP allows (1432 bytes) and then some, so an oversized one is seen
// whole enough to be counted as too long rather than silently cut to a valid size.
constexpr std::size_t slot_size = 2048;
// Datagrams read per wake-up before yielding to other handlers on the loop.
constexpr std::size_t max_batches_per_wakeup = 16;

ip_mreqn membership_request(const MulticastMembership& membership) {
    const auto group = parse_ipv4(membership.group);
    if (!group) {
        throw std::system_error(
            std::make_error_code(std::errc::invalid_argument),
            "multicast group '" + membership.group + "' is not an IPv4 address");
    }
    ip_mreqn request{};
    request.imr_multiaddr.s_addr = htonl(*group);
    if (!membership.interface.empty()) {
        if (auto address = parse_ipv4(membership.interface)) {
            request.imr_address.s_addr = htonl(*address);
        } else {
            const unsigned index = if_nametoindex(membership.interface.c_str());
            if (index == 0) {
                throw std::system_error(errno, std::generic_category(),
                                        "multicast interface '" + membership.interface + "'");
            }
            request.imr_ifindex = static_cast<int>(index);
        }
    }
    return request;
}

std::string_view interface_name(const MulticastMembership& membership) {
    if (membership.interface.empty()) return "the default interface";
    return membership.interface;
}

void join_group(int fd, const MulticastMembership& membership) {
    const auto request = membership_request(membership);
    if (setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &request, sizeof request) != 0) {
        throw std::system_error(errno, std::generic_category(),
                                "cannot join multicast group " + membership.group);
    }
    spdlog::info("joined multicast group {} on {}", membership.group, interface_name(membership));
}

/// Never throws: a group that cannot be left (its interface went, and the kernel left it then)
/// is logged.
void leave_group(int fd, const MulticastMembership& membership) {
    try {
        const auto request = membership_request(membership);
        if (setsockopt(fd, IPPROTO_IP, IP_DROP_MEMBERSHIP, &request, sizeof request) != 0) {
            throw std::system_error(errno, std::generic_category(), "setsockopt");
        }
        spdlog::info("left multicast group {} on {}", membership.group, interface_name(membership));
    } catch (const std::system_error& e) {
        spdlog::warn("cannot leave multicast group {} on {}: {}", membership.group,
                     interface_name(membership), e.what());
    }
}

bool contains(const std::vector<MulticastMembership>& list, const MulticastMembership& one) {
    return std::find(list.begin(), list.end(), one) != list.end();
}

/// The destination address IP_PKTINFO gave for a received message, host byte order; 0 if none.
std::uint32_t destination_of(msghdr& header) {
    if (header.msg_control == nullptr) return 0;
    for (cmsghdr* c = CMSG_FIRSTHDR(&header); c != nullptr; c = CMSG_NXTHDR(&header, c)) {
        if (c->cmsg_level == IPPROTO_IP && c->cmsg_type == IP_PKTINFO) {
            in_pktinfo info{};
            std::memcpy(&info, CMSG_DATA(c), sizeof info);
            return ntohl(info.ipi_addr.s_addr);
        }
    }
    return 0;
}

}  // namespace

Receiver::Receiver(boost::asio::any_io_executor executor, const ReceiverOptions& options)
    : socket_(executor), batch_(options.batch == 0 ? 1 : options.batch) {
    namespace ip = boost::asio::ip;
    boost::system::error_code ec;
    const auto address = ip::make_address_v4(options.bind, ec);
    if (ec) {
        throw std::system_error(ec, "eip.bind '" + options.bind + "' is not an IPv4 address");
    }
    const ip::udp::endpoint endpoint(address, options.port);
    socket_.open(ip::udp::v4());
    socket_.set_option(ip::udp::socket::reuse_address(true));
    socket_.non_blocking(true);
    const int fd = socket_.native_handle();
    const int rcvbuf = options.receive_buffer_bytes;
    if (rcvbuf > 0) setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    socket_.bind(endpoint, ec);
    if (ec) {
        throw std::system_error(
            ec, "cannot bind UDP " + options.bind + ":" + std::to_string(options.port));
    }
    for (const auto& membership : options.multicast) join_group(fd, membership);
    memberships_ = options.multicast;
    if (options.destinations) {
        const int on = 1;
        if (setsockopt(fd, IPPROTO_IP, IP_PKTINFO, &on, sizeof on) != 0) {
            throw std::system_error(errno, std::generic_category(), "cannot set IP_PKTINFO");
        }
        controls_.resize(batch_);
    }

    storage_.resize(batch_ * slot_size);
    messages_.resize(batch_);
    iovecs_.resize(batch_);
    sources_.resize(batch_);
    for (std::size_t i = 0; i < batch_; ++i) {
        iovecs_[i].iov_base = storage_.data() + i * slot_size;
        iovecs_[i].iov_len = slot_size;
    }
}

Receiver::~Receiver() { stop(); }

void Receiver::start(Handler handler) {
    handler_ = std::move(handler);
    do_wait();
}

void Receiver::start_with_destinations(DestinationHandler handler) {
    destination_handler_ = std::move(handler);
    do_wait();
}

void Receiver::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void Receiver::set_multicast(const std::vector<MulticastMembership>& memberships) {
    const int fd = socket_.native_handle();
    // Left first: a group moved from the default interface to the one the kernel chose anyway
    // would otherwise be joined twice (EADDRINUSE).
    std::vector<MulticastMembership> left;
    for (const auto& membership : memberships_) {
        if (contains(memberships, membership)) continue;
        leave_group(fd, membership);
        left.push_back(membership);
    }
    std::vector<MulticastMembership> joined;
    try {
        for (const auto& membership : memberships) {
            if (contains(memberships_, membership) || contains(joined, membership)) continue;
            join_group(fd, membership);
            joined.push_back(membership);
        }
    } catch (const std::system_error&) {
        for (const auto& membership : joined) leave_group(fd, membership);
        for (const auto& membership : left) {
            try {
                join_group(fd, membership);
            } catch (const std::system_error& e) {
                spdlog::error("cannot join multicast group {} again: {}", membership.group,
                              e.what());
            }
        }
        throw;
    }
    memberships_ = memberships;
}

std::uint16_t Receiver::local_port() const {
    boost::system::error_code ec;
    return socket_.local_endpoint(ec).port();
}

void Receiver::do_wait() {
    socket_.async_wait(boost::asio::ip::udp::socket::wait_read,
                       [this](const boost::system::error_code& error) { on_readable(error); });
}

void Receiver::on_readable(const boost::system::error_code& error) {
    if (error == boost::asio::error::operation_aborted || stopped_) return;
    if (error) {
        ++stats_.errors;
        if (const auto count = error_log_.record(std::chrono::steady_clock::now())) {
            spdlog::error("UDP receive wait failed: {} ({} since the last line)", error.message(),
                          count);
        }
    } else {
        for (std::size_t i = 0; i < max_batches_per_wakeup; ++i) {
            if (drain() < batch_) break;
        }
    }
    if (!stopped_) do_wait();
}

std::size_t Receiver::drain() {
    for (std::size_t i = 0; i < batch_; ++i) {
        auto& header = messages_[i].msg_hdr;
        header = {};
        header.msg_name = &sources_[i];
        header.msg_namelen = sizeof(sockaddr_in);
        header.msg_iov = &iovecs_[i];
        header.msg_iovlen = 1;
        if (!controls_.empty()) {
            header.msg_control = controls_[i].bytes;
            header.msg_controllen = sizeof controls_[i].bytes;
        }
        messages_[i].msg_len = 0;
    }
    const int fd = socket_.native_handle();
    const int count = ::recvmmsg(fd, messages_.data(), static_cast<unsigned>(batch_),
                                 MSG_DONTWAIT | MSG_TRUNC, nullptr);
    if (count < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            ++stats_.errors;
            const int failure = errno;
            if (const auto count = error_log_.record(std::chrono::steady_clock::now())) {
                spdlog::error("recvmmsg failed: {} ({} since the last line)",
                              std::strerror(failure), count);
            }
        }
        return 0;
    }
    ++stats_.batches;
    for (int i = 0; i < count; ++i) {
        auto& message = messages_[static_cast<std::size_t>(i)];
        std::size_t length = message.msg_len;
        const bool truncated = (message.msg_hdr.msg_flags & MSG_TRUNC) != 0 || length > slot_size;
        if (truncated) {
            ++stats_.truncated;
            length = slot_size;
        }
        const auto& source = sources_[static_cast<std::size_t>(i)];
        const Endpoint from{ntohl(source.sin_addr.s_addr), ntohs(source.sin_port)};
        ++stats_.datagrams;
        const std::span<const std::byte> bytes(
            storage_.data() + static_cast<std::size_t>(i) * slot_size, length);
        if (destination_handler_) {
            destination_handler_(bytes, from, destination_of(message.msg_hdr), truncated);
        } else {
            handler_(bytes, from, truncated);
        }
        if (stopped_) break;
    }
    return static_cast<std::size_t>(count);
}

}  // namespace eip2mqtt::adapters::udp
