#include "eip2mqtt/core/command/decode.hpp"

#include "core/command/detail/byte_io.hpp"

namespace eip2mqtt::core::command {
namespace {

using detail::ByteReader;

wire::ExchangeKey key_at(ByteReader& in, std::size_t offset) {
    return {wire::ProducerId{in.dotted(offset)}, in.u32(offset + 4)};
}

// Fixed-size requests: anything shorter is truncated, anything longer malformed.
Result<RequestBody, DecodeError> fixed_request(const PduHeader& header, ByteReader& in) {
    const auto exact = [&](std::size_t size) -> std::optional<DecodeError> {
        if (in.size() < size) return DecodeError::truncated;
        if (in.size() > size) return DecodeError::malformed;
        return std::nullopt;
    };
    switch (header.type) {
        case PduType::retrieve_config_request:
        case PduType::statistics_request: {
            if (const auto error = exact(16)) return fail(*error);
            const auto key = key_at(in, 8);
            if (header.type == PduType::statistics_request) return {StatisticsRequest{key}};
            return {RetrieveConfigRequest{key}};
        }
        case PduType::summary_request:
            if (const auto error = exact(12)) return fail(*error);
            return {SummaryRequest{in.u8(8)}};
        case PduType::capabilities_request:
            // §9.3: some requesters send the header alone; the producer id is then 0.
            if (in.size() == header_size) return {CapabilitiesRequest{}};
            if (const auto error = exact(12)) return fail(*error);
            return {CapabilitiesRequest{wire::ProducerId{in.dotted(8)}}};
        default:
            return fail(DecodeError::not_a_request);
    }
}

Result<ExchangeConfig, DecodeError> config_response(ByteReader& in) {
    if (in.size() < config_response_size) return fail(DecodeError::truncated);
    ExchangeConfig config;
    config.key = key_at(in, 8);
    config.period_ms = in.u32(16);
    config.destination_type = static_cast<DestinationType>(in.u16(22));
    config.destination = in.dotted(24);
    config.state = static_cast<ExchangeState>(in.u16(56));
    config.length = in.u16(58);
    config.port = in.u16(64);
    config.config_type = in.u16(66);
    config.signature = in.u16(68);
    config.mode = static_cast<ExchangeMode>(in.u16(70));
    config.config_data = in.u16(74);
    return config;
}

Result<SummaryPage, DecodeError> summary_response(ByteReader& in) {
    if (in.size() < summary_fixed_size) return fail(DecodeError::truncated);
    SummaryPage page;
    page.index = in.u8(8);
    page.producer_id = wire::ProducerId{in.dotted(9)};
    page.total_cells = in.u16(13);
    const std::size_t count = in.u16(15);
    if (in.size() < summary_fixed_size + count * summary_cell_size) {
        return fail(DecodeError::truncated);
    }
    page.cells.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t at = summary_fixed_size + i * summary_cell_size;
        page.cells.push_back({key_at(in, at), static_cast<ExchangeMode>(in.u8(at + 8)),
                              static_cast<ExchangeState>(in.u16(at + 10)), in.u32(at + 12)});
    }
    return page;
}

Result<Capabilities, DecodeError> capabilities_response(ByteReader& in) {
    if (in.size() < 28) return fail(DecodeError::truncated);
    return Capabilities{wire::ProducerId{in.dotted(8)}, in.u32(16), in.u32(20), in.u16(26),
                        in.text(28, max_text_size)};
}

Result<ExchangeStatistics, DecodeError> statistics_response(ByteReader& in) {
    if (in.size() < statistics_response_size) return fail(DecodeError::truncated);
    return ExchangeStatistics{
        key_at(in, 8), in.u32(16), in.u32(20), static_cast<ExchangeState>(in.u32(24)),
        in.u32(28),    in.u32(32), in.u32(36), in.u32(40)};
}

Result<CommandNak, DecodeError> nak_response(ByteReader& in) {
    if (in.size() < nak_fixed_size) return fail(DecodeError::truncated);
    const auto echo = in.bytes(20, nak_echo_size);
    return CommandNak{key_at(in, 8),
                      in.u16(16),
                      {echo.begin(), echo.end()},
                      in.text(nak_fixed_size, max_text_size)};
}

template <class T>
Result<ResponseBody, DecodeError> widen(Result<T, DecodeError> result) {
    if (!result) return fail(result.error());
    return ResponseBody{std::move(result).value()};
}

}  // namespace

Result<PduHeader, DecodeError> decode_header(std::span<const std::byte> bytes) {
    if (bytes.size() < header_size) return fail(DecodeError::no_header);
    if (bytes.size() > max_pdu_size) return fail(DecodeError::oversized);
    ByteReader in(bytes);
    PduHeader header;
    header.flag = in.u8(1);
    header.request_id = in.u16(2);
    header.version = in.u8(4);
    header.status = in.u8(5);
    header.length = in.u16(6);
    if (header.version != protocol_version) return fail(DecodeError::wrong_version);
    if (header.length != bytes.size()) return fail(DecodeError::wrong_length);
    const auto type = pdu_type_of(in.u8(0));
    if (!type) return fail(DecodeError::unknown_type);
    header.type = *type;
    return header;
}

Result<Request, DecodeError> decode_request(std::span<const std::byte> bytes) {
    auto header = decode_header(bytes);
    if (!header) return fail(header.error());
    if (!is_request(header->type)) return fail(DecodeError::not_a_request);
    ByteReader in(bytes);
    switch (header->type) {
        case PduType::read_request:
        case PduType::write_request:
        case PduType::masked_write_request: {
            auto data = decode_data_pdu(*header, bytes);
            if (!data) return fail(data.error());
            return Request{*header, std::move(data).value()};
        }
        default: {
            auto body = fixed_request(*header, in);
            if (!body) return fail(body.error());
            return Request{*header, std::move(body).value()};
        }
    }
}

Result<Response, DecodeError> decode_response(std::span<const std::byte> bytes) {
    auto header = decode_header(bytes);
    if (!header) return fail(header.error());
    if (is_request(header->type)) return fail(DecodeError::not_a_response);
    ByteReader in(bytes);
    auto body = [&]() -> Result<ResponseBody, DecodeError> {
        switch (header->type) {
            case PduType::retrieve_config_response:
                return widen(config_response(in));
            case PduType::summary_response:
                return widen(summary_response(in));
            case PduType::capabilities_response:
                return widen(capabilities_response(in));
            case PduType::statistics_response:
                return widen(statistics_response(in));
            case PduType::nak:
                return widen(nak_response(in));
            default:
                return widen(decode_data_pdu(*header, bytes));
        }
    }();
    if (!body) return fail(body.error());
    return Response{*header, std::move(body).value()};
}

}  // namespace eip2mqtt::core::command
