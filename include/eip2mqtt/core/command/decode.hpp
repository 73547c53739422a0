#pragma once
/// Decoding of command PDUs received on UDP 7937 (docs/protocol.md §9): the responder decodes
/// requests, the requester (`discover`) responses. Both never read past the bytes given and
/// bound every allocation by the PDU's size.

#include <cstddef>
#include <span>
#include <variant>

#include "eip2mqtt/core/command/command_nak.hpp"
#include "eip2mqtt/core/command/data_pdus.hpp"
#include "eip2mqtt/core/command/decode_error.hpp"
#include "eip2mqtt/core/command/exchange_pdus.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::core::command {

using RequestBody = std::variant<RetrieveConfigRequest, SummaryRequest, CapabilitiesRequest,
                                 StatisticsRequest, DataPdu>;
struct Request {
    PduHeader header;
    RequestBody body;
};

using ResponseBody = std::variant<ExchangeConfig, SummaryPage, Capabilities, ExchangeStatistics,
                                  CommandNak, DataPdu>;
struct Response {
    PduHeader header;
    ResponseBody body;
};

/// The header checks every PDU passes (§9.1), in this order: no_header (< 8 bytes), oversized
/// (> 1400), wrong_version, wrong_length (bytes 6-7 differ from `bytes.size()`), unknown_type.
Result<PduHeader, DecodeError> decode_header(std::span<const std::byte> bytes);

/// A request, or why not: the header checks, then not_a_request for a response or a NAK, then
/// truncated or malformed for its body (§9.3, §9.4).
Result<Request, DecodeError> decode_request(std::span<const std::byte> bytes);

/// A response or a NAK, or why not: the header checks, not_a_response for a request, then its
/// body. A Read response with a non-zero status carries no cell.
Result<Response, DecodeError> decode_response(std::span<const std::byte> bytes);

/// The Read, Write or Masked Write request or response of `header.type` (decode_data.cpp).
Result<DataPdu, DecodeError> decode_data_pdu(const PduHeader& header,
                                             std::span<const std::byte> bytes);

}  // namespace eip2mqtt::core::command
