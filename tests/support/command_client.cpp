#include "tests/support/command_client.hpp"

namespace eip2mqtt::test {

std::optional<core::command::Response> CommandClient::ask(std::uint16_t port,
                                                          const std::vector<std::byte>& request,
                                                          std::chrono::milliseconds timeout) {
    const auto request_id = static_cast<std::uint16_t>(std::to_integer<unsigned>(request[2]) |
                                                       std::to_integer<unsigned>(request[3]) << 8);
    udp_.send_to(port, request);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) return std::nullopt;
        const auto bytes = udp_.receive(left);
        if (!bytes) return std::nullopt;
        auto response = core::command::decode_response(*bytes);
        if (response && response->header.request_id == request_id) return std::move(*response);
    }
}

}  // namespace eip2mqtt::test
