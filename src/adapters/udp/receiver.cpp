#include "eip2mqtt/adapters/udp/receiver.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio/error.hpp>
#include <boost/asio/ip/address_v4.hpp>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "eip2mqtt/adapters/udp/port_holders.hpp"

namespace eip2mqtt::adapters::udp {
namespace {

namespace ip = boost::asio::ip;

// Room for any datagram EIP allows (1432 bytes) and then some, so an oversized one is seen
// whole enough to be counted as too long rather than silently cut to a valid size.
constexpr std::size_t slot_size = 2048;
// Datagrams read per wake-up before yielding to other handlers on the loop.
constexpr std::size_t max_batches_per_wakeup = 16;

ip::address_v4 ipv4(const std::string& text, const char* what) {
    boost::system::error_code ec;
    const auto address = ip::make_address_v4(text, ec);
    if (ec) throw std::system_error(ec, std::string(what) + " '" + text + "' is not IPv4");
    return address;
}

/// Opens a non-blocking IPv4 UDP socket with the receive buffer asked for.
void open(ip::udp::socket& socket, int receive_buffer_bytes) {
    socket.open(ip::udp::v4());
    socket.non_blocking(true);
    if (receive_buffer_bytes > 0) {
        setsockopt(socket.native_handle(), SOL_SOCKET, SO_RCVBUF, &receive_buffer_bytes,
                   sizeof receive_buffer_bytes);
    }
}

/// A system_error whose message is written whole, the error's own words in the middle.
class BindError : public std::system_error {
public:
    BindError(std::error_code code, std::string message)
        : std::system_error(code), message_(std::move(message)) {}
    const char* what() const noexcept override { return message_.c_str(); }

private:
    std::string message_;
};

/// The start-up error for a bind that failed; a port in use names who holds it.
[[noreturn]] void bind_failed(const boost::system::error_code& ec, const std::string& address,
                              std::uint16_t port) {
    const auto where = fmt::format("cannot bind UDP {}:{}", address, port);
    if (ec != boost::asio::error::address_in_use) throw std::system_error(ec, where);
    auto holders = describe_udp_port_holders(port);
    if (holders.empty()) holders = "held by another socket";
    throw BindError(ec, fmt::format("{}: {}, {}. A gateway keeps its port to itself, so that no "
                                    "other program takes its datagrams: stop the other one, or "
                                    "give this gateway another eip.port (`eip2mqtt sniff` "
                                    "watches a port without taking it)",
                                    where, ec.message(), holders));
}

}  // namespace

Receiver::Receiver(boost::asio::any_io_executor executor, const ReceiverOptions& options)
    : executor_(std::move(executor)),
      receive_buffer_bytes_(options.receive_buffer_bytes),
      batch_(options.batch == 0 ? 1 : options.batch),
      clock_(*options.clock) {
    open_unicast(options);
    // The wildcard socket receives every group joined on it; beside it no other socket could
    // bind the port, ours included.
    wildcard_ = ipv4(options.bind, "eip.bind").is_unspecified();
    for (const auto& membership : options.multicast) {
        memberships_.emplace_back(membership, join(membership));
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

void Receiver::open_unicast(const ReceiverOptions& options) {
    const auto address = ipv4(options.bind, "eip.bind");
    auto& socket = sockets_.emplace_back(executor_);
    open(socket, options.receive_buffer_bytes);
    // No SO_REUSEADDR: Linux lets two sockets share a port only when both set it, and then
    // hands each unicast datagram to one of them.
    boost::system::error_code ec;
    socket.bind(ip::udp::endpoint(address, options.port), ec);
    if (ec) bind_failed(ec, options.bind, options.port);
}

std::size_t Receiver::open_group(const MulticastMembership& membership) {
    const auto group = ipv4(membership.group, "multicast group");
    const auto port = local_port();
    ip::udp::socket socket(executor_);
    open(socket, receive_buffer_bytes_);
    // Shared on purpose: each socket bound to the group gets its own copy of every datagram.
    socket.set_option(ip::udp::socket::reuse_address(true));
    const int fd = socket.native_handle();
    const int off = 0;
    setsockopt(fd, IPPROTO_IP, IP_MULTICAST_ALL, &off, sizeof off);
    boost::system::error_code ec;
    socket.bind(ip::udp::endpoint(group, port), ec);
    if (ec) bind_failed(ec, membership.group, port);
    join_group(fd, membership);
    sockets_.push_back(std::move(socket));
    return sockets_.size() - 1;
}

std::size_t Receiver::join(const MulticastMembership& membership) {
    if (!wildcard_) return open_group(membership);
    join_group(sockets_.front().native_handle(), membership);
    return wildcard_joined;
}

void Receiver::leave(const MulticastMembership& membership, std::size_t socket) {
    if (socket == wildcard_joined) {
        leave_group(sockets_.front().native_handle(), membership);
        return;
    }
    // Closing the group's own socket leaves the group; its wait completes aborted.
    boost::system::error_code ignored;
    sockets_[socket].close(ignored);
    spdlog::info("left multicast group {}", membership.group);
}

void Receiver::set_multicast(const std::vector<MulticastMembership>& memberships) {
    const auto wanted = [&](const MulticastMembership& m) {
        return std::find(memberships.begin(), memberships.end(), m) != memberships.end();
    };
    const auto held = [](const auto& list, const MulticastMembership& m) {
        return std::any_of(list.begin(), list.end(), [&](const auto& h) { return h.first == m; });
    };
    // Left first: a group moved from the default interface to the one the kernel chose anyway
    // would otherwise be joined twice on the wildcard socket (EADDRINUSE).
    decltype(memberships_) kept, left, joined;
    for (auto& entry : memberships_) (wanted(entry.first) ? kept : left).push_back(entry);
    for (const auto& [membership, socket] : left) leave(membership, socket);
    try {
        for (const auto& membership : memberships) {
            if (held(kept, membership) || held(joined, membership)) continue;
            joined.emplace_back(membership, join(membership));
            if (handler_ && joined.back().second != wildcard_joined) do_wait(joined.back().second);
        }
    } catch (const std::system_error&) {
        for (const auto& [membership, socket] : joined) leave(membership, socket);
        for (const auto& [membership, socket] : left) {
            try {
                const auto index = join(membership);
                if (handler_ && index != wildcard_joined) do_wait(index);
                kept.emplace_back(membership, index);
            } catch (const std::system_error& e) {
                spdlog::error("cannot join multicast group {} again: {}", membership.group,
                              e.what());
            }
        }
        memberships_ = std::move(kept);
        throw;
    }
    kept.insert(kept.end(), joined.begin(), joined.end());
    memberships_ = std::move(kept);
}

Receiver::~Receiver() { stop(); }

void Receiver::start(Handler handler) {
    handler_ = std::move(handler);
    for (std::size_t i = 0; i < sockets_.size(); ++i) do_wait(i);
}

void Receiver::stop() {
    stopped_ = true;
    boost::system::error_code ignored;
    for (auto& socket : sockets_) socket.close(ignored);
}

std::uint16_t Receiver::local_port() const {
    boost::system::error_code ec;
    return sockets_.front().local_endpoint(ec).port();
}

void Receiver::do_wait(std::size_t socket) {
    sockets_[socket].async_wait(
        ip::udp::socket::wait_read,
        [this, socket](const boost::system::error_code& error) { on_readable(socket, error); });
}

void Receiver::on_readable(std::size_t socket, const boost::system::error_code& error) {
    if (error == boost::asio::error::operation_aborted || stopped_) return;
    if (error) {
        ++stats_.errors;
        if (const auto count = error_log_.record(clock_.monotonic())) {
            spdlog::error("UDP receive wait failed: {} ({} since the last line)", error.message(),
                          count);
        }
    } else {
        read_socket(socket);
    }
    if (!stopped_) do_wait(socket);
}

void Receiver::read_socket(std::size_t socket) {
    const int fd = sockets_[socket].native_handle();
    for (std::size_t i = 0; i < max_batches_per_wakeup; ++i) {
        if (drain(fd) < batch_ || stopped_) break;
    }
}

void Receiver::read_pending() {
    if (!handler_) return;
    for (std::size_t i = 0; i < sockets_.size() && !stopped_; ++i) {
        if (sockets_[i].is_open()) read_socket(i);
    }
}

std::size_t Receiver::drain(int fd) {
    for (std::size_t i = 0; i < batch_; ++i) {
        auto& header = messages_[i].msg_hdr;
        header = {};
        header.msg_name = &sources_[i];
        header.msg_namelen = sizeof(sockaddr_in);
        header.msg_iov = &iovecs_[i];
        header.msg_iovlen = 1;
        messages_[i].msg_len = 0;
    }
    const int count = ::recvmmsg(fd, messages_.data(), static_cast<unsigned>(batch_),
                                 MSG_DONTWAIT | MSG_TRUNC, nullptr);
    if (count < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            ++stats_.errors;
            const int failure = errno;
            if (const auto count = error_log_.record(clock_.monotonic())) {
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
        handler_({storage_.data() + static_cast<std::size_t>(i) * slot_size, length}, from,
                 truncated);
        if (stopped_) break;
    }
    return static_cast<std::size_t>(count);
}

}  // namespace eip2mqtt::adapters::udp
