#include "eip2mqtt/core/command/encode.hpp"

#include <algorithm>
#include <cassert>
#include <string_view>

#include "core/command/detail/byte_io.hpp"
#include "core/command/detail/header_io.hpp"

namespace eip2mqtt::core::command {
namespace {

using detail::ByteWriter;
using detail::finish;
using detail::put_header;

// Starts a PDU of `type` whose whole size is `size` (reserved up front).
std::vector<std::byte> start(PduHeader& header, PduType type, std::size_t size) {
    header.type = type;
    std::vector<std::byte> pdu;
    pdu.reserve(size);
    ByteWriter out(pdu);
    put_header(out, header);
    return pdu;
}

void put_key(ByteWriter& out, const wire::ExchangeKey& key) {
    out.dotted(key.producer_id.value);
    out.u32(key.exchange_id);
}

/// Retrieve Configuration and Statistics requests carry an exchange's key and nothing else.
std::vector<std::byte> key_request(PduHeader& header, PduType type, const wire::ExchangeKey& key) {
    auto pdu = start(header, type, 16);
    ByteWriter out(pdu);
    put_key(out, key);
    return finish(std::move(pdu));
}

std::string_view cut(const std::string& text) {
    return std::string_view(text).substr(0, std::min(text.size(), max_text_size));
}

}  // namespace

std::vector<std::byte> encode(PduHeader header, const RetrieveConfigRequest& request) {
    return key_request(header, PduType::retrieve_config_request, request.key);
}

std::vector<std::byte> encode(PduHeader header, const SummaryRequest& request) {
    auto pdu = start(header, PduType::summary_request, 12);
    ByteWriter out(pdu);
    out.u8(request.index);
    out.zeros(3);
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const CapabilitiesRequest& request) {
    auto pdu = start(header, PduType::capabilities_request, 12);
    ByteWriter out(pdu);
    out.dotted(request.producer_id.value);
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const StatisticsRequest& request) {
    return key_request(header, PduType::statistics_request, request.key);
}

// docs/protocol.md §9.3, Retrieve Configuration response: 76 bytes.
std::vector<std::byte> encode(PduHeader header, const ExchangeConfig& config) {
    auto pdu = start(header, PduType::retrieve_config_response, config_response_size);
    ByteWriter out(pdu);
    put_key(out, config.key);
    out.u32(config.period_ms);
    out.u16(0);
    out.u16(static_cast<std::uint16_t>(config.destination_type));
    out.dotted(config.destination);
    out.zeros(28);
    out.u16(static_cast<std::uint16_t>(config.state));
    out.u16(config.length);
    out.zeros(4);
    out.u16(config.port);
    out.u16(config.config_type);
    out.u16(config.signature);
    out.u16(static_cast<std::uint16_t>(config.mode));
    out.u16(0);
    out.u16(config.config_data);
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const SummaryPage& page) {
    assert(page.cells.size() <= max_summary_cells);
    auto pdu = start(header, PduType::summary_response,
                     summary_fixed_size + page.cells.size() * summary_cell_size);
    ByteWriter out(pdu);
    out.u8(page.index);
    out.dotted(page.producer_id.value);
    out.u16(page.total_cells);
    out.u16(static_cast<std::uint16_t>(page.cells.size()));
    for (const auto& cell : page.cells) {
        put_key(out, cell.key);
        out.u8(static_cast<std::uint8_t>(cell.mode));
        out.u8(0);
        out.u16(static_cast<std::uint16_t>(cell.state));
        out.u32(cell.period_ms);
    }
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const Capabilities& capabilities) {
    const auto identification = cut(capabilities.identification);
    auto pdu = start(header, PduType::capabilities_response, 28 + identification.size() + 1);
    ByteWriter out(pdu);
    out.dotted(capabilities.producer_id.value);
    out.zeros(4);
    out.u32(capabilities.max_exchanges);
    out.u32(capabilities.capabilities);
    out.zeros(2);
    out.u16(capabilities.config_type);
    out.text(identification);
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const ExchangeStatistics& statistics) {
    auto pdu = start(header, PduType::statistics_response, statistics_response_size);
    ByteWriter out(pdu);
    put_key(out, statistics.key);
    for (const std::uint32_t value :
         {statistics.config_time_s, statistics.due_time_ms,
          static_cast<std::uint32_t>(statistics.state), statistics.length, statistics.messages,
          statistics.missed, statistics.refresh_errors, 0u}) {
        out.u32(value);
    }
    return finish(std::move(pdu));
}

std::vector<std::byte> encode(PduHeader header, const CommandNak& nak) {
    const auto error = cut(nak.error);
    auto pdu = start(header, PduType::nak, nak_fixed_size + error.size() + 1);
    ByteWriter out(pdu);
    put_key(out, nak.key);
    out.u16(nak.error_code);
    out.u16(0);
    const auto echo = std::min(nak.offending.size(), nak_echo_size);
    out.bytes(std::span(nak.offending).first(echo));
    out.zeros(nak_echo_size - echo);
    out.text(error);
    return finish(std::move(pdu));
}

}  // namespace eip2mqtt::core::command
