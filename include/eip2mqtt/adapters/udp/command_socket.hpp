#pragma once
/// The UDP socket of the command protocol (docs/protocol.md §9): the responder's on port 7937,
/// or a requester's on an ephemeral port. Receives one datagram at a time (requests are few and
/// rate-limited) into a buffer one byte larger than the largest PDU, so that an oversized
/// datagram is seen as such; sends without blocking and never queues.
///
/// Threading: constructed, started and stopped on the loop; the handler runs on the loop.

#include <array>
#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::adapters::udp {

struct CommandSocketStats {
    std::uint64_t received = 0;
    std::uint64_t sent = 0;
    std::uint64_t send_errors = 0;
};

class CommandSocket {
public:
    /// `datagram` views the receive buffer and is valid only during the call; a datagram over
    /// the largest PDU arrives cut to max_pdu_size + 1 bytes.
    using Handler = std::function<void(std::span<const std::byte> datagram, const Endpoint& from)>;

    /// Binds `bind`:`port` (0: ephemeral) without SO_REUSEADDR: the port is this process's.
    /// Throws std::system_error naming the address on failure (a start-up error).
    CommandSocket(boost::asio::any_io_executor executor, const std::string& bind,
                  std::uint16_t port);

    void start(Handler handler);
    /// Closes the socket; a pending receive completes with operation_aborted and stops quietly.
    void stop();
    /// Sends one datagram to `to`; false (and counted) when the kernel refused it.
    bool send_to(std::span<const std::byte> datagram, const Endpoint& to);

    std::uint16_t local_port() const;
    const CommandSocketStats& stats() const { return stats_; }

private:
    void do_receive();
    void on_receive(const boost::system::error_code& error, std::size_t size);

    boost::asio::ip::udp::socket socket_;
    boost::asio::ip::udp::endpoint from_;
    std::array<std::byte, core::command::max_pdu_size + 1> buffer_{};
    Handler handler_;
    CommandSocketStats stats_;
    bool stopped_ = false;
};

}  // namespace eip2mqtt::adapters::udp
