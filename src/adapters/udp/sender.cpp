#include "eip2mqtt/adapters/udp/sender.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <boost/asio/ip/multicast.hpp>
#include <system_error>

namespace eip2mqtt::adapters::udp {

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
    sockaddr_in destination{};
    destination.sin_family = AF_INET;
    destination.sin_addr.s_addr = htonl(to.address);
    destination.sin_port = htons(to.port);
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

}  // namespace eip2mqtt::adapters::udp
