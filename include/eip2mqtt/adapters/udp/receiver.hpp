#pragma once
/// Receives EIP datagrams on one UDP socket (Boost.Asio for readiness, recvmmsg to read a batch
/// per system call). Buffers are allocated once; the steady path allocates nothing.
///
/// Threading: constructed, started and stopped on the loop; the handler runs on the loop.

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/uio.h>

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::udp {

struct MulticastMembership {
    std::string group;      ///< e.g. 224.0.7.1
    std::string interface;  ///< interface name (eth0) or IPv4 address; empty: the kernel's choice

    friend bool operator==(const MulticastMembership&, const MulticastMembership&) = default;
};

struct ReceiverOptions {
    std::string bind = "0.0.0.0";
    std::uint16_t port = 18246;  ///< 0: an ephemeral port (tests)
    std::vector<MulticastMembership> multicast;
    std::size_t batch = 64;                      ///< datagrams per recvmmsg
    int receive_buffer_bytes = 8 * 1024 * 1024;  ///< SO_RCVBUF request (the kernel may cap it)
    /// Ask the kernel for each datagram's destination address (IP_PKTINFO), handed to a
    /// DestinationHandler. Off for the gateway, which identifies exchanges by their key alone.
    bool destinations = false;
};

struct ReceiverStats {
    std::uint64_t datagrams = 0;
    std::uint64_t batches = 0;    ///< recvmmsg calls that returned data
    std::uint64_t truncated = 0;  ///< larger than the buffer (MSG_TRUNC): handed on at full size
    std::uint64_t errors = 0;
};

class Receiver {
public:
    /// `datagram` views the receive buffer and is valid only during the call.
    using Handler = std::function<void(std::span<const std::byte> datagram, const Endpoint& from,
                                       bool truncated)>;
    /// The same with the address the datagram was sent to (IPv4, host byte order: the group of
    /// a multicast, the broadcast address of a broadcast), 0 when the kernel did not say.
    using DestinationHandler =
        std::function<void(std::span<const std::byte> datagram, const Endpoint& from,
                           std::uint32_t destination, bool truncated)>;

    /// Opens and binds the socket and joins the multicast groups; throws std::system_error with
    /// a message naming the address on failure (a start-up error).
    Receiver(boost::asio::any_io_executor executor, const ReceiverOptions& options);
    ~Receiver();

    void start(Handler handler);
    /// start() for ReceiverOptions::destinations (without it, every destination is 0).
    void start_with_destinations(DestinationHandler handler);
    /// Closes the socket; a pending wait completes with operation_aborted and stops quietly.
    void stop();
    /// Leaves the groups joined that `memberships` lacks and joins those it adds (a reload),
    /// on the bound socket. All or nothing: when a group cannot be joined, the groups are put
    /// back as they were and std::system_error names the group.
    void set_multicast(const std::vector<MulticastMembership>& memberships);

    std::uint16_t local_port() const;
    const ReceiverStats& stats() const { return stats_; }

private:
    void do_wait();
    void on_readable(const boost::system::error_code& error);
    std::size_t drain();

    boost::asio::ip::udp::socket socket_;
    /// Room for one IP_PKTINFO control message.
    struct Control {
        alignas(struct ::cmsghdr) unsigned char bytes[CMSG_SPACE(sizeof(struct ::in_pktinfo))];
    };

    Handler handler_;
    DestinationHandler destination_handler_;
    std::size_t batch_;
    std::vector<std::byte> storage_;
    std::vector<struct ::mmsghdr> messages_;
    std::vector<struct ::iovec> iovecs_;
    std::vector<struct ::sockaddr_in> sources_;
    std::vector<Control> controls_;  ///< one per slot with ReceiverOptions::destinations
    std::vector<MulticastMembership> memberships_;  ///< joined, in the order asked
    ReceiverStats stats_;
    core::ThrottledLog error_log_;  ///< a failing socket fails on every wake-up
    bool stopped_ = false;
};

}  // namespace eip2mqtt::adapters::udp
