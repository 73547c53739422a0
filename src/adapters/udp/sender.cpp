#include "eip2mqtt/adapters/udp/sender.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/udp.h>

#include <algorithm>
#include <boost/asio/ip/multicast.hpp>
#include <cerrno>
#include <cstring>
#include <system_error>
#include <tuple>

namespace eip2mqtt::adapters::udp {
namespace {

// Linux's limits for one UDP GSO message: UDP_MAX_SEGMENTS is 64 before 6.4 (128 after), and
// the whole must fit in one IP datagram.
constexpr std::size_t max_gso_segments = 64;
constexpr std::size_t max_gso_bytes = 65000;
// One UDP_SEGMENT control message, in 8-byte words (CMSG_SPACE of a u16 is 24 on x86-64).
constexpr std::size_t control_words = (CMSG_SPACE(sizeof(std::uint16_t)) + 7) / 8;

sockaddr_in to_sockaddr(const Endpoint& to) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(to.address);
    address.sin_port = htons(to.port);
    return address;
}

}  // namespace

Sender::Sender(boost::asio::any_io_executor executor, const SenderOptions& options)
    : socket_(executor) {
    namespace ip = boost::asio::ip;
    boost::system::error_code ec;
    const auto address = ip::make_address_v4(options.bind, ec);
    if (ec) throw std::system_error(ec, "send address '" + options.bind + "'");
    socket_.open(ip::udp::v4());
    socket_.set_option(ip::udp::socket::broadcast(true));
    socket_.set_option(ip::multicast::hops(options.multicast_ttl));
    socket_.set_option(ip::multicast::enable_loopback(options.multicast_loop));
    if (!options.multicast_interface.empty()) {
        const auto interface = ip::make_address_v4(options.multicast_interface, ec);
        if (ec) {
            throw std::system_error(ec, "multicast interface '" + options.multicast_interface +
                                            "' is not an IPv4 address");
        }
        socket_.set_option(ip::multicast::outbound_interface(interface));
    }
    if (options.port != 0) socket_.set_option(ip::udp::socket::reuse_address(true));
    socket_.bind(ip::udp::endpoint(address, options.port), ec);
    if (ec) {
        throw std::system_error(
            ec, "cannot bind UDP sender to " + options.bind + ":" + std::to_string(options.port));
    }
    socket_.non_blocking(true);
}

bool Sender::send_to(std::span<const std::byte> datagram, const Endpoint& to) {
    const auto destination = to_sockaddr(to);
    const auto sent =
        ::sendto(socket_.native_handle(), datagram.data(), datagram.size(), MSG_DONTWAIT,
                 reinterpret_cast<const sockaddr*>(&destination), sizeof destination);
    if (sent != static_cast<ssize_t>(datagram.size())) {
        ++stats_.errors;
        return false;
    }
    ++stats_.sent;
    return true;
}

void Sender::group_batch(std::span<const OutgoingDatagram> batch) {
    const std::size_t n = batch.size();
    // Equal size to the same destination, next to each other: each run becomes one message.
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i) order_[i] = i;
    const auto key = [&](std::size_t i) {
        return std::make_tuple(batch[i].to.address, batch[i].to.port, batch[i].bytes.size());
    };
    std::stable_sort(order_.begin(), order_.end(),
                     [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    groups_.clear();
    for (std::size_t k = 0; k < n; ++k) {
        const auto size = batch[order_[k]].bytes.size();
        if (!groups_.empty()) {
            auto& group = groups_.back();
            if (gso_ && key(order_[group.first]) == key(order_[k]) &&
                group.count < max_gso_segments && group.bytes + size <= max_gso_bytes) {
                ++group.count;
                group.bytes += size;
                continue;
            }
        }
        groups_.push_back({k, 1, size});
    }
}

void Sender::build_messages(std::span<const OutgoingDatagram> batch) {
    const std::size_t n = batch.size();
    const std::size_t m = groups_.size();
    addresses_.resize(m);
    iovecs_.resize(n);
    messages_.resize(m);
    controls_.assign(m * control_words, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const auto& bytes = batch[order_[k]].bytes;
        // sendmmsg does not write through iov_base; the cast only satisfies the C signature.
        iovecs_[k] = {const_cast<std::byte*>(bytes.data()), bytes.size()};
    }
    for (std::size_t g = 0; g < m; ++g) {
        const auto& group = groups_[g];
        addresses_[g] = to_sockaddr(batch[order_[group.first]].to);
        auto& header = messages_[g].msg_hdr;
        messages_[g] = {};
        header.msg_name = &addresses_[g];
        header.msg_namelen = sizeof(sockaddr_in);
        header.msg_iov = &iovecs_[group.first];
        header.msg_iovlen = group.count;
        if (group.count > 1) {
            // The kernel cuts the message every `size` bytes: one datagram per iovec.
            header.msg_control = &controls_[g * control_words];
            header.msg_controllen = CMSG_SPACE(sizeof(std::uint16_t));
            cmsghdr* cmsg = CMSG_FIRSTHDR(&header);
            cmsg->cmsg_level = SOL_UDP;
            cmsg->cmsg_type = UDP_SEGMENT;
            cmsg->cmsg_len = CMSG_LEN(sizeof(std::uint16_t));
            const auto size = static_cast<std::uint16_t>(iovecs_[group.first].iov_len);
            std::memcpy(CMSG_DATA(cmsg), &size, sizeof size);
        }
    }
}

std::size_t Sender::send_batch(std::span<const OutgoingDatagram> batch, std::vector<bool>& sent) {
    sent.assign(batch.size(), false);
    group_batch(batch);
    build_messages(batch);
    const std::size_t m = groups_.size();

    std::size_t count = 0;
    const auto mark_sent = [&](const Group& group) {
        for (std::size_t k = group.first; k < group.first + group.count; ++k) {
            sent[order_[k]] = true;
        }
        count += group.count;
        stats_.sent += group.count;
    };
    std::size_t next = 0;
    while (next < m) {
        const int r = ::sendmmsg(socket_.native_handle(), messages_.data() + next,
                                 static_cast<unsigned>(m - next), MSG_DONTWAIT);
        if (r < 0) {
            if (errno == EINTR) continue;
            // sendmmsg reports the error of the first message it could not send: that one is
            // refused (EAGAIN on a full socket buffer, EMSGSIZE, ENETUNREACH...); the messages
            // after it are tried again by the next call.
            const auto& group = groups_[next];
            if (group.count > 1) {
                // GSO needs checksum offload on the route's device; without it (EIO) or on an
                // old kernel (EINVAL, ENOPROTOOPT) send one by one, now and from now on.
                if (errno == EIO || errno == EINVAL || errno == ENOPROTOOPT) gso_ = false;
                count += send_group_one_by_one(batch, group, sent);
            } else {
                ++stats_.errors;
            }
            ++next;
            continue;
        }
        for (int i = 0; i < r; ++i, ++next) {
            // UDP sends a message whole or not at all; a short count would be a refusal.
            if (messages_[next].msg_len == groups_[next].bytes) {
                mark_sent(groups_[next]);
            } else {
                stats_.errors += groups_[next].count;
            }
        }
        if (r == 0) {  // cannot happen for m > 0; never spin
            for (; next < m; ++next) stats_.errors += groups_[next].count;
        }
    }
    return count;
}

std::size_t Sender::send_group_one_by_one(std::span<const OutgoingDatagram> batch,
                                          const Group& group, std::vector<bool>& sent) {
    std::size_t count = 0;
    for (std::size_t k = group.first; k < group.first + group.count; ++k) {
        const auto i = order_[k];
        sent[i] = send_to(batch[i].bytes, batch[i].to);
        count += sent[i] ? 1 : 0;
    }
    return count;
}

}  // namespace eip2mqtt::adapters::udp
