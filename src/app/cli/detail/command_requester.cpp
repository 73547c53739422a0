#include "app/cli/detail/command_requester.hpp"

#include "eip2mqtt/core/command/address_proof.hpp"
#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/response_match.hpp"
#include "eip2mqtt/core/printable.hpp"

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
    if (answer_ || challenge_ || !request_ || from.address != node_address_) return;
    if (const auto token = core::command::challenge_token(datagram)) {
        const auto header = core::command::decode_header(datagram);
        if (header && header->request_id == request_->header.request_id &&
            header->flag == request_->header.flag &&
            header->type == core::command::response_type_of(request_->header.type)) {
            challenge_ = token;
            io_.stop();
        }
        return;
    }
    auto response = core::command::decode_response(datagram);
    if (!response) return;
    // Late answers to an earlier request, or answers to another one: not this request's.
    if (!core::command::answers_request(*request_, request_bytes_, *response)) {
        ++mismatched_;
        return;
    }
    answer_ = std::move(response).value();
    io_.stop();
}

void CommandRequester::attempt(const adapters::udp::Endpoint& node) {
    request_ = core::command::decode_request(request_bytes_).value();
    answer_.reset();
    challenge_.reset();
    for (int attempt = 0; attempt < attempts_ && !answer_ && !challenge_; ++attempt) {
        socket_.send_to(request_bytes_, node);
        io_.restart();
        io_.run_for(timeout_);
    }
}

core::Result<core::command::Response, std::string> CommandRequester::exchange(
    std::vector<std::byte> request, const adapters::udp::Endpoint& node) {
    node_address_ = node.address;
    request_bytes_ = std::move(request);
    mismatched_ = 0;
    // docs/protocol.md §9.7: a node that asked for a token gets it in every later request; a
    // challenge is met once, with the token it carries.
    if (const auto token = tokens_.find(node.address); token != tokens_.end()) {
        core::command::carry_token(request_bytes_, token->second);
    }
    attempt(node);
    if (challenge_) {
        tokens_[node.address] = *challenge_;
        core::command::carry_token(request_bytes_, *challenge_);
        attempt(node);
    }
    if (challenge_) return core::fail(std::string("the node asks again for a proof of address"));
    if (!answer_) {
        return core::fail(no_answer() + (mismatched_ == 0 ? std::string()
                                                          : "; " + std::to_string(mismatched_) +
                                                                " answers to another request "
                                                                "ignored"));
    }
    const auto& header = answer_->header;
    if (const auto* nak = std::get_if<core::command::CommandNak>(&answer_->body)) {
        return core::fail("NAK " + (nak->error.empty() ? "code " + std::to_string(nak->error_code)
                                                       : core::printable_ascii(nak->error, 80)));
    }
    if (header.status != 0) {
        const auto status = core::command::command_status_of(header.status);
        return core::fail("status " + (status ? std::string(core::command::to_string(*status))
                                              : std::to_string(header.status)));
    }
    return std::move(*answer_);
}

}  // namespace eip2mqtt::app::detail
