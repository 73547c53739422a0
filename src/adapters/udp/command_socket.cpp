#include "eip2mqtt/adapters/udp/command_socket.hpp"

#include <sys/socket.h>

#include <boost/asio/buffer.hpp>
#include <system_error>

namespace eip2mqtt::adapters::udp {

CommandSocket::CommandSocket(boost::asio::any_io_executor executor, const std::string& bind,
                             std::uint16_t port)
    : socket_(executor) {
    namespace ip = boost::asio::ip;
    boost::system::error_code ec;
    const auto address = ip::make_address_v4(bind, ec);
    if (ec) throw std::system_error(ec, "command address '" + bind + "'");
    socket_.open(ip::udp::v4());
    socket_.bind(ip::udp::endpoint(address, port), ec);
    if (ec) {
        throw std::system_error(
            ec, "cannot bind the command port " + bind + ":" + std::to_string(port));
    }
}

void CommandSocket::start(Handler handler) {
    handler_ = std::move(handler);
    do_receive();
}

void CommandSocket::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    socket_.close(ignored);
}

void CommandSocket::do_receive() {
    socket_.async_receive_from(boost::asio::buffer(buffer_), from_,
                               [this](const boost::system::error_code& error, std::size_t size) {
                                   on_receive(error, size);
                               });
}

void CommandSocket::on_receive(const boost::system::error_code& error, std::size_t size) {
    if (error == boost::asio::error::operation_aborted || stopped_) return;
    // A datagram larger than the buffer fails with message_size on some systems and arrives
    // cut on others: either way it is the buffer's size, and so oversized.
    if (!error || error == boost::asio::error::message_size) {
        ++stats_.received;
        const Endpoint from{from_.address().to_v4().to_uint(), from_.port()};
        handler_(std::span<const std::byte>(buffer_.data(), error ? buffer_.size() : size), from);
    }
    if (!stopped_) do_receive();
}

bool CommandSocket::send_to(std::span<const std::byte> datagram, const Endpoint& to) {
    namespace ip = boost::asio::ip;
    boost::system::error_code ec;
    const ip::udp::endpoint destination(ip::address_v4(to.address), to.port);
    socket_.send_to(boost::asio::buffer(datagram.data(), datagram.size()), destination,
                    MSG_DONTWAIT, ec);
    if (ec) {
        ++stats_.send_errors;
        return false;
    }
    ++stats_.sent;
    return true;
}

std::uint16_t CommandSocket::local_port() const {
    boost::system::error_code ec;
    const auto endpoint = socket_.local_endpoint(ec);
    return ec ? 0 : endpoint.port();
}

}  // namespace eip2mqtt::adapters::udp
