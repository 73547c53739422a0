#pragma once
/// Sends EIP datagrams from one UDP socket: unicast, broadcast (SO_BROADCAST) or multicast
/// (TTL and interface configurable). Sends are non-blocking and never queue: a datagram the
/// kernel refuses is counted, as the protocol repairs a loss with the next period.
///
/// Threading: used from the loop only.

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/uio.h>

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/ip/udp.hpp>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/udp/endpoint.hpp"

namespace eip2mqtt::adapters::udp {

struct SenderOptions {
    std::string bind = "0.0.0.0";
    std::uint16_t port = 0;  ///< source port; 0: ephemeral
    int multicast_ttl = 1;
    std::string multicast_interface;  ///< IPv4 address of the outgoing interface; empty: default
    bool multicast_loop = true;       ///< let local consumers (and tests) see our multicast
};

/// One datagram of a batch: the bytes stay owned by the caller until send_batch returns.
struct OutgoingDatagram {
    std::span<const std::byte> bytes;
    Endpoint to;
};

struct SenderStats {
    std::uint64_t sent = 0;
    std::uint64_t errors = 0;
};

class Sender {
public:
    /// Opens the socket (broadcast allowed); throws std::system_error on failure.
    Sender(boost::asio::any_io_executor executor, const SenderOptions& options);

    /// Sends one datagram; false (and counted) when the kernel refused it.
    bool send_to(std::span<const std::byte> datagram, const Endpoint& to);

    /// Sends every datagram of `batch` with as few sendmmsg calls as the kernel allows (one
    /// when all succeed). Datagrams of equal size to the same destination go as one UDP GSO
    /// message (UDP_SEGMENT): the kernel builds and routes one buffer and cuts it into the
    /// datagrams, which is most of the cost per datagram; consumers see ordinary datagrams.
    /// Order is kept per destination, not across destinations. `sent[i]` (resized to the
    /// batch) says whether datagram i left: a datagram the kernel refuses is counted and
    /// skipped, and the rest still go, so each exchange's counters and write results stay
    /// exact. Where the kernel or the route refuses GSO, the datagrams are sent one by one and
    /// GSO is not tried again. Returns how many were sent.
    std::size_t send_batch(std::span<const OutgoingDatagram> batch, std::vector<bool>& sent);

    const SenderStats& stats() const { return stats_; }

private:
    boost::asio::ip::udp::socket socket_;
    SenderStats stats_;
    /// One sendmmsg message: `count` datagrams from `first` in order_.
    struct Group {
        std::size_t first;
        std::size_t count;
        std::size_t bytes;
    };
    /// Fills order_ and groups_ for `batch`.
    void group_batch(std::span<const OutgoingDatagram> batch);
    /// Fills the sendmmsg messages of groups_ (addresses, iovecs, GSO control).
    void build_messages(std::span<const OutgoingDatagram> batch);
    std::size_t send_group_one_by_one(std::span<const OutgoingDatagram> batch, const Group& group,
                                      std::vector<bool>& sent);

    bool gso_ = true;  ///< UDP_SEGMENT accepted so far
    // Reused by send_batch, so a steady batch size allocates nothing.
    std::vector<std::size_t> order_;  ///< batch indices grouped by destination and size
    std::vector<Group> groups_;
    std::vector<sockaddr_in> addresses_;   ///< per group
    std::vector<iovec> iovecs_;            ///< per datagram, in order_
    std::vector<mmsghdr> messages_;        ///< per group
    std::vector<std::uint64_t> controls_;  ///< per group: room for one UDP_SEGMENT cmsg
};

}  // namespace eip2mqtt::adapters::udp
