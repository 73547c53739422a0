#include "tests/support/command_client.hpp"

#include "eip2mqtt/core/command/address_proof.hpp"

namespace eip2mqtt::test {
namespace {

std::uint16_t request_id_of(const std::vector<std::byte>& request) {
    return static_cast<std::uint16_t>(std::to_integer<unsigned>(request[2]) |
                                      std::to_integer<unsigned>(request[3]) << 8);
}

}  // namespace

void CommandClient::carry_token(std::vector<std::byte>& request) const {
    core::command::carry_token(request, *token_);
}

std::optional<core::command::Response> CommandClient::ask(std::uint16_t port,
                                                          const std::vector<std::byte>& request,
                                                          std::chrono::milliseconds timeout) {
    auto sent = request;
    udp_.send_to(port, sent);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    bool challenged = false;
    while (true) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return std::nullopt;
        const auto bytes = udp_.receive(left);
        if (!bytes) return std::nullopt;
        const auto token = core::command::challenge_token(*bytes);
        if (token && !challenged && request_id_of(*bytes) == request_id_of(sent)) {
            challenged = true;
            token_ = token;
            carry_token(sent);
            udp_.send_to(port, sent);
            continue;
        }
        auto response = core::command::decode_response(*bytes);
        if (response && response->header.request_id == request_id_of(sent)) {
            return std::move(*response);
        }
    }
}

}  // namespace eip2mqtt::test
