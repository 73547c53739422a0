#pragma once
/// A requester of the command protocol on UDP 7937 for integration tests (docs/protocol.md §9):
/// sends a request to a port on 127.0.0.1 from its own socket and waits for the response that
/// carries the request's id. It meets a challenge as `discover` does (§9.7): the request goes
/// again with the token, which every later request carries.

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {

class CommandClient {
public:
    /// Binds `address` (host order; 127.0.0.2 is another source on this host).
    explicit CommandClient(std::uint32_t address = 0x7F000001) : udp_(0, address) {}

    /// The encoded request of `type` carrying `body`, with a fresh request id.
    template <class Body>
    std::vector<std::byte> request(core::command::PduType type, const Body& body) {
        core::command::PduHeader header;
        header.type = type;
        header.request_id = ++request_id_;
        auto bytes = core::command::encode(header, body);
        if (token_) carry_token(bytes);
        return bytes;
    }

    /// Sends `request` to `port` and returns the response with its id, or nullopt after
    /// `timeout`. Datagrams with another id (answers to earlier requests) are skipped.
    std::optional<core::command::Response> ask(
        std::uint16_t port, const std::vector<std::byte>& request,
        std::chrono::milliseconds timeout = std::chrono::seconds(5));

    template <class Body>
    std::optional<core::command::Response> ask(std::uint16_t port, core::command::PduType type,
                                               const Body& body) {
        return ask(port, request(type, body));
    }

    UdpClient& udp() { return udp_; }
    /// The token a challenge gave, if one came.
    std::optional<std::uint32_t> token() const { return token_; }

private:
    void carry_token(std::vector<std::byte>& request) const;

    UdpClient udp_;
    std::uint16_t request_id_ = 0;
    std::optional<std::uint32_t> token_;
};

}  // namespace eip2mqtt::test
