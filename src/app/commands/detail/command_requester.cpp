#include "app/commands/detail/command_requester.hpp"

#include "eip2mqtt/core/command/command_status.hpp"

namespace eip2mqtt::app::detail {

CommandRequester::CommandRequester(std::chrono::milliseconds timeout, int attempts)
    : timeout_(timeout), attempts_(attempts), socket_(io_.get_executor(), "0.0.0.0", 0) {
    socket_.start([this](std::span<const std::byte> datagram, const adapters::udp::Endpoint& from) {
        on_datagram(datagram, from);
    });
}

std::string CommandRequester::no_answer() const {
    return "no answer after " + std::to_string(attempts_) +
           (attempts_ == 1 ? " attempt" : " attempts") + " of " + std::to_string(timeout_.count()) +
           " ms";
}

void CommandRequester::on_datagram(std::span<const std::byte> datagram,
                                   const adapters::udp::Endpoint& from) {
    if (answer_ || from.address != node_address_) return;
    auto response = core::command::decode_response(datagram);
    // Late answers to an earlier attempt carry an older id: they are not this request's.
    if (!response || response->header.request_id != request_id_) return;
    if (response->header.type != expected_ &&
        response->header.type != core::command::PduType::nak) {
        return;
    }
    answer_ = std::move(response).value();
    io_.stop();
}

core::Result<core::command::Response, std::string> CommandRequester::exchange(
    const std::vector<std::byte>& request, const adapters::udp::Endpoint& node) {
    node_address_ = node.address;
    expected_ = *core::command::response_type_of(
        *core::command::pdu_type_of(std::to_integer<std::uint8_t>(request[0])));
    answer_.reset();
    for (int attempt = 0; attempt < attempts_ && !answer_; ++attempt) {
        socket_.send_to(request, node);
        io_.restart();
        io_.run_for(timeout_);
    }
    if (!answer_) return core::fail(no_answer());
    const auto& header = answer_->header;
    if (const auto* nak = std::get_if<core::command::CommandNak>(&answer_->body)) {
        return core::fail(
            "NAK " + (nak->error.empty() ? "code " + std::to_string(nak->error_code) : nak->error));
    }
    if (header.status != 0) {
        const auto status = core::command::command_status_of(header.status);
        return core::fail("status " + (status ? std::string(core::command::to_string(*status))
                                              : std::to_string(header.status)));
    }
    return std::move(*answer_);
}

}  // namespace eip2mqtt::app::detail
