#include "eip2mqtt/core/command/command_nak.hpp"

#include <algorithm>

#include "core/command/detail/byte_io.hpp"

namespace eip2mqtt::core::command {
namespace {

// Where the request names its exchange, if its type has one (§9.3, §9.4).
wire::ExchangeKey key_of(std::span<const std::byte> request) {
    detail::ByteReader in(request);
    std::size_t at = 0;
    switch (pdu_type_of(in.u8(0)).value_or(PduType::nak)) {
        case PduType::retrieve_config_request:
        case PduType::statistics_request:
            at = 8;
            break;
        case PduType::read_request:
        case PduType::write_request:
        case PduType::masked_write_request:
            at = 12;
            break;
        default:
            return {};
    }
    const wire::ExchangeKey key{wire::ProducerId{in.dotted(at)}, in.u32(at + 4)};
    return in.overrun() ? wire::ExchangeKey{} : key;
}

}  // namespace

std::optional<NakReply> make_nak(std::span<const std::byte> request, DecodeError error) {
    const auto code = nak_code(error);
    if (!code || request.size() < header_size) return std::nullopt;
    detail::ByteReader in(request);
    // §9.5: a response or a NAK is never answered, even one with a bad version or length, so
    // that two nodes can never keep answering each other.
    if (const auto type = pdu_type_of(in.u8(0)); type && !is_request(*type)) return std::nullopt;
    PduHeader header;
    header.type = PduType::nak;
    header.flag = in.u8(1);
    header.request_id = in.u16(2);
    const auto echo = request.first(std::min(request.size(), nak_echo_size));
    return NakReply{
        header,
        CommandNak{
            key_of(request), *code, {echo.begin(), echo.end()}, std::string(to_string(error))}};
}

}  // namespace eip2mqtt::core::command
