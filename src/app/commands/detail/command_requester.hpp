#pragma once
// Asks nodes on the command port and waits for each answer (`discover`; docs/protocol.md §9):
// one request at a time, each sent again after `timeout` up to `attempts` times. An answer is
// taken from any port of the node's address (responders may answer from another port than
// 7937) when it carries the request's id and is its response or a NAK.

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <optional>
#include <string>

#include "eip2mqtt/adapters/udp/command_socket.hpp"
#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::app::detail {

class CommandRequester {
public:
    CommandRequester(std::chrono::milliseconds timeout, int attempts);

    /// The answer of `node` to `body`, or why there is none: no answer after every attempt, a
    /// NAK with its reason, or the status of an error response.
    template <class Body>
    core::Result<core::command::Response, std::string> ask(const Body& body,
                                                           const adapters::udp::Endpoint& node) {
        core::command::PduHeader header;
        header.request_id = ++request_id_;
        return exchange(core::command::encode(header, body), node);
    }

    /// Why nothing came: `no answer after 3 attempts of 500 ms`.
    std::string no_answer() const;

private:
    core::Result<core::command::Response, std::string> exchange(
        const std::vector<std::byte>& request, const adapters::udp::Endpoint& node);
    void on_datagram(std::span<const std::byte> datagram, const adapters::udp::Endpoint& from);

    std::chrono::milliseconds timeout_;
    int attempts_;
    boost::asio::io_context io_;
    adapters::udp::CommandSocket socket_;
    std::uint16_t request_id_ = 0;
    // What the answer must match while a request waits.
    std::uint32_t node_address_ = 0;
    core::command::PduType expected_ = core::command::PduType::nak;
    std::optional<core::command::Response> answer_;
};

}  // namespace eip2mqtt::app::detail
