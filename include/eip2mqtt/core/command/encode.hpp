#pragma once
/// Encoding of command PDUs (docs/protocol.md §9). Each function writes the header it is given
/// with the PDU's length filled in; the bodies with a type of their own also set the type. Every
/// PDU is exactly as long as its content: a response is never larger than needed.

#include <cstddef>
#include <vector>

#include "eip2mqtt/core/command/command_nak.hpp"
#include "eip2mqtt/core/command/data_pdus.hpp"
#include "eip2mqtt/core/command/exchange_pdus.hpp"
#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::core::command {

std::vector<std::byte> encode(PduHeader header, const RetrieveConfigRequest& request);
std::vector<std::byte> encode(PduHeader header, const SummaryRequest& request);
/// 12 bytes: the producer id asked about (0 when unknown).
std::vector<std::byte> encode(PduHeader header, const CapabilitiesRequest& request);
std::vector<std::byte> encode(PduHeader header, const StatisticsRequest& request);

std::vector<std::byte> encode(PduHeader header, const ExchangeConfig& config);
/// `page.cells` must hold at most max_summary_cells.
std::vector<std::byte> encode(PduHeader header, const SummaryPage& page);
/// The identification is cut to max_text_size characters and ends with a NUL.
std::vector<std::byte> encode(PduHeader header, const Capabilities& capabilities);
std::vector<std::byte> encode(PduHeader header, const ExchangeStatistics& statistics);
/// The echo is cut or zero-padded to 16 bytes; the error string is cut to max_text_size.
std::vector<std::byte> encode(PduHeader header, const CommandNak& nak);

/// Read, Write or Masked Write of `header.type` (encode_data.cpp): a request's cells as its type
/// carries them; a Read response's cells with their data, unless its status is an error; Write
/// and Masked Write responses, and every error response, as the fixed part alone. Each cell's
/// data and mask must hold `length` bytes where they are sent.
std::vector<std::byte> encode(PduHeader header, const DataPdu& pdu);

}  // namespace eip2mqtt::core::command
