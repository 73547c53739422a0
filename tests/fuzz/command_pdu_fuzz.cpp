// Fuzzes the command-protocol codec (UDP 7937 takes whatever the network sends): every input is
// decoded as a request and as a response. What decodes must encode back to a PDU that decodes
// to the same value; what does not gets the NAK a responder would send, which must itself
// decode and stay small.

#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "eip2mqtt/core/command/command_nak.hpp"
#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"

namespace {

using namespace eip2mqtt::core::command;

template <class Decoded, class Decode>
void round_trip(const Decoded& decoded, Decode decode) {
    const auto bytes =
        std::visit([&](const auto& body) { return encode(decoded.header, body); }, decoded.body);
    if (bytes.size() > max_pdu_size) __builtin_trap();
    const auto again = decode(bytes);
    if (!again || again->body != decoded.body) __builtin_trap();
}

void answer(std::span<const std::byte> bytes) {
    const auto request = decode_request(bytes);
    if (request) {
        round_trip(*request, [](std::span<const std::byte> b) { return decode_request(b); });
        return;
    }
    (void)to_string(request.error());
    const auto reply = make_nak(bytes, request.error());
    if (!reply) return;
    const auto nak = encode(reply->header, reply->nak);
    if (nak.size() > 52) __builtin_trap();
    const auto decoded = decode_response(nak);
    if (!decoded || !std::holds_alternative<CommandNak>(decoded->body)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    answer(bytes);
    const auto response = decode_response(bytes);
    if (response) {
        round_trip(*response, [](std::span<const std::byte> b) { return decode_response(b); });
    }
    return 0;
}
