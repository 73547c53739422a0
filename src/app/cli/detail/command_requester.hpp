#pragma once
// Asks nodes on the command port and waits for each answer (`discover`; docs/protocol.md §9):
// one request at a time, each sent again after `timeout` up to `attempts` times. An answer is
// taken from any port of the node's address (responders may answer from another port than
// 7937) when it answers the request asked (core::command::answers_request): its id, its type
// or a NAK, and the exchange or page asked for. A challenge (§9.7) is met once per request: the
// request goes again carrying the token, which later requests to that node carry too.

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <map>
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
    /// NAK with its reason, or the status of an error response. Text the node told is escaped
    /// (core::printable_ascii).
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
        std::vector<std::byte> request, const adapters::udp::Endpoint& node);
    /// Sends `request_` up to `attempts_` times until an answer or a challenge comes.
    void attempt(const adapters::udp::Endpoint& node);
    void on_datagram(std::span<const std::byte> datagram, const adapters::udp::Endpoint& from);

    std::chrono::milliseconds timeout_;
    int attempts_;
    boost::asio::io_context io_;
    adapters::udp::CommandSocket socket_;
    std::uint16_t request_id_ = 0;
    /// The token each node gave in a challenge, by address.
    std::map<std::uint32_t, std::uint32_t> tokens_;
    // What the answer must match while a request waits.
    std::uint32_t node_address_ = 0;
    std::vector<std::byte> request_bytes_;
    std::optional<core::command::Request> request_;
    std::optional<core::command::Response> answer_;
    std::optional<std::uint32_t> challenge_;
    std::size_t mismatched_ = 0;  ///< answers from the node that were not to this request
};

}  // namespace eip2mqtt::app::detail
