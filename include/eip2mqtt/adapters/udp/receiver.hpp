#pragma once
/// Receives EIP datagrams (Boost.Asio for readiness, recvmmsg to read a batch per system call).
/// Buffers are allocated once; the steady path allocates nothing.
///
/// The port is the gateway's own: the unicast socket is bound without SO_REUSEADDR or
/// SO_REUSEPORT, so no other process can bind the port beside it and take its datagrams (Linux
/// hands a unicast datagram to one socket only), and a second gateway on the port fails at start.
/// Multicast is delivered to every socket bound to the group, so it can be shared: with a
/// specific `bind` address each group gets a socket of its own, bound to the group with
/// SO_REUSEADDR, beside which other programs on this host may consume the same group. With
/// `bind` 0.0.0.0 the wildcard socket owns every address of the port and joins the groups itself.
///
/// Threading: constructed, started and stopped on the loop; the handler runs on the loop.

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/uio.h>

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/adapters/udp/multicast.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::udp {

struct ReceiverOptions {
    std::string bind = "0.0.0.0";
    std::uint16_t port = 18246;  ///< 0: an ephemeral port (tests)
    std::vector<MulticastMembership> multicast;
    std::size_t batch = 64;                      ///< datagrams per recvmmsg
    int receive_buffer_bytes = 8 * 1024 * 1024;  ///< SO_RCVBUF request (the kernel may cap it)
    /// Times the throttled error log; outlives the Receiver.
    const core::Clock* clock = &adapters::clock::system_clock();
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

    /// Opens and binds the sockets and joins the multicast groups; throws std::system_error with
    /// a message naming the address on failure (a start-up error). A port another process
    /// holds is refused with that process named (port_holders.hpp).
    Receiver(boost::asio::any_io_executor executor, const ReceiverOptions& options);
    ~Receiver();

    void start(Handler handler);
    /// Closes the sockets; pending waits complete with operation_aborted and stop quietly.
    void stop();
    /// Leaves the groups joined that `memberships` lacks and joins those it adds (a reload): on
    /// the wildcard socket, or each on a socket of its own. All or nothing: when a group cannot
    /// be joined, the groups are put back as they were and std::system_error names the group.
    void set_multicast(const std::vector<MulticastMembership>& memberships);

    /// Reads what the sockets hold now, without waiting (bounded as one wake-up is). Called
    /// before the exchanges' timeouts are judged: a datagram that arrived in time but waits
    /// unread behind a busy loop is taken first, so that a busy gateway never calls an exchange
    /// stale that was not.
    void read_pending();

    std::uint16_t local_port() const;
    const ReceiverStats& stats() const { return stats_; }

private:
    void open_unicast(const ReceiverOptions& options);
    /// Opens, binds and joins a group's own socket (a specific `bind`); returns its index.
    std::size_t open_group(const MulticastMembership& membership);
    /// Joins `membership` where it belongs; the socket index it holds, or `wildcard_joined`.
    std::size_t join(const MulticastMembership& membership);
    /// Leaves what join() made of `membership`; never throws.
    void leave(const MulticastMembership& membership, std::size_t socket);
    void do_wait(std::size_t socket);
    void on_readable(std::size_t socket, const boost::system::error_code& error);
    /// Up to max_batches_per_wakeup batches from one socket.
    void read_socket(std::size_t socket);
    std::size_t drain(int fd);

    boost::asio::any_io_executor executor_;
    /// [0] the unicast socket; then one per multicast group when bound to a specific address.
    /// A group left by a reload leaves its socket closed in place: indices never move, and a
    /// deque never moves a socket with a wait in flight when a reload adds one.
    std::deque<boost::asio::ip::udp::socket> sockets_;
    static constexpr std::size_t wildcard_joined = 0;
    bool wildcard_ = false;
    int receive_buffer_bytes_ = 0;
    /// Joined, in the order asked, each with the socket that holds it.
    std::vector<std::pair<MulticastMembership, std::size_t>> memberships_;

    Handler handler_;
    std::size_t batch_;
    std::vector<std::byte> storage_;
    std::vector<struct ::mmsghdr> messages_;
    std::vector<struct ::iovec> iovecs_;
    std::vector<struct ::sockaddr_in> sources_;
    ReceiverStats stats_;
    const core::Clock& clock_;
    core::ThrottledLog error_log_;  ///< a failing socket fails on every wake-up
    bool stopped_ = false;
};

}  // namespace eip2mqtt::adapters::udp
