#include "eip2mqtt/adapters/udp/sender.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <boost/asio/ip/multicast.hpp>
#include <cerrno>
#include <system_error>

namespace eip2mqtt::adapters::udp {
namespace {

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

std::size_t Sender::send_batch(std::span<const OutgoingDatagram> batch, std::vector<bool>& sent) {
    const std::size_t n = batch.size();
    sent.assign(n, false);
    addresses_.resize(n);
    iovecs_.resize(n);
    messages_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        addresses_[i] = to_sockaddr(batch[i].to);
        // sendmmsg does not write through iov_base; the cast only satisfies the C signature.
        iovecs_[i] = {const_cast<std::byte*>(batch[i].bytes.data()), batch[i].bytes.size()};
        messages_[i] = {};
        messages_[i].msg_hdr.msg_name = &addresses_[i];
        messages_[i].msg_hdr.msg_namelen = sizeof(sockaddr_in);
        messages_[i].msg_hdr.msg_iov = &iovecs_[i];
        messages_[i].msg_hdr.msg_iovlen = 1;
    }
    std::size_t count = 0;
    std::size_t next = 0;
    while (next < n) {
        const int r = ::sendmmsg(socket_.native_handle(), messages_.data() + next,
                                 static_cast<unsigned>(n - next), MSG_DONTWAIT);
        if (r < 0) {
            if (errno == EINTR) continue;
            // sendmmsg reports the error of the first datagram it could not send: that one
            // is refused (EAGAIN on a full socket buffer, EMSGSIZE, ENETUNREACH...); the
            // datagrams after it are tried again by the next call.
            ++stats_.errors;
            ++next;
            continue;
        }
        for (int i = 0; i < r; ++i, ++next) {
            // UDP sends a datagram whole or not at all; a short count would be a refusal.
            if (messages_[next].msg_len == batch[next].bytes.size()) {
                sent[next] = true;
                ++count;
                ++stats_.sent;
            } else {
                ++stats_.errors;
            }
        }
        if (r == 0) {  // cannot happen for n > 0; never spin
            stats_.errors += n - next;
            break;
        }
    }
    return count;
}

}  // namespace eip2mqtt::adapters::udp
