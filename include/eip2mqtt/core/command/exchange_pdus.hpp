#pragma once
/// The PDUs that describe a node's exchanges (docs/protocol.md §9.3): Retrieve Configuration,
/// Summary, Capabilities and Statistics, requests and responses, as plain values.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "eip2mqtt/core/command/pdu_header.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::command {

/// Mode of an exchange in Retrieve Configuration and Summary (§9.3).
enum class ExchangeMode : std::uint16_t { produced = 1, consumed = 2 };

/// Configuration state (§9.3): `active` when the exchange produces, or consumes fresh data;
/// `idle` when it is configured but not (stale, never received, mismatched).
enum class ExchangeState : std::uint32_t { idle = 1, active = 2 };

/// Destination type of Retrieve Configuration (§9.3).
enum class DestinationType : std::uint16_t { none = 0, unicast = 1, multicast = 2, broadcast = 3 };

/// Capability bits of a Capabilities response (§9.3; eip2mqtt's, the manual defines none).
namespace capability {
inline constexpr std::uint32_t produces = 1u << 0;
inline constexpr std::uint32_t consumes = 1u << 1;
inline constexpr std::uint32_t read = 1u << 2;
inline constexpr std::uint32_t write = 1u << 3;
inline constexpr std::uint32_t masked_write = 1u << 4;
}  // namespace capability

/// The longest identification or NAK error string, in characters (§9.3, §9.5).
inline constexpr std::size_t max_text_size = 80;

struct RetrieveConfigRequest {
    wire::ExchangeKey key;
    friend bool operator==(const RetrieveConfigRequest&, const RetrieveConfigRequest&) = default;
};

/// The body of a Retrieve Configuration response (76 bytes with its header).
struct ExchangeConfig {
    wire::ExchangeKey key;
    std::uint32_t period_ms = 0;
    DestinationType destination_type = DestinationType::none;
    std::uint32_t destination = 0;  ///< IPv4, held like a ProducerId (first octet high)
    ExchangeState state = ExchangeState::idle;
    std::uint16_t length = 0;  ///< data bytes
    std::uint16_t port = wire::default_port;
    std::uint16_t config_type = 0;
    std::uint16_t signature = 0;  ///< major << 8 | minor, as wire::Signature::to_wire
    ExchangeMode mode = ExchangeMode::produced;
    std::uint16_t config_data = 0;
    friend bool operator==(const ExchangeConfig&, const ExchangeConfig&) = default;
};
inline constexpr std::size_t config_response_size = 76;

struct SummaryRequest {
    std::uint8_t index = 0;  ///< the first cell wanted
    friend bool operator==(const SummaryRequest&, const SummaryRequest&) = default;
};

struct SummaryCell {
    wire::ExchangeKey key;
    ExchangeMode mode = ExchangeMode::produced;
    ExchangeState state = ExchangeState::idle;
    std::uint32_t period_ms = 0;
    friend bool operator==(const SummaryCell&, const SummaryCell&) = default;
};

/// One page of a node's exchanges: cells index .. index + cells.size() - 1 of total_cells.
struct SummaryPage {
    std::uint8_t index = 0;
    wire::ProducerId producer_id;  ///< the responding node's
    std::uint16_t total_cells = 0;
    std::vector<SummaryCell> cells;
    friend bool operator==(const SummaryPage&, const SummaryPage&) = default;
};
inline constexpr std::size_t summary_fixed_size = 17;
inline constexpr std::size_t summary_cell_size = 16;
/// The most cells one Summary response carries within 1400 bytes.
inline constexpr std::size_t max_summary_cells =
    (max_pdu_size - summary_fixed_size) / summary_cell_size;

struct CapabilitiesRequest {
    wire::ProducerId producer_id;
    friend bool operator==(const CapabilitiesRequest&, const CapabilitiesRequest&) = default;
};

struct Capabilities {
    wire::ProducerId producer_id;
    std::uint32_t max_exchanges = 0;
    std::uint32_t capabilities = 0;  ///< capability:: bits
    std::uint16_t config_type = 0;
    std::string identification;  ///< at most max_text_size characters
    friend bool operator==(const Capabilities&, const Capabilities&) = default;
};

struct StatisticsRequest {
    wire::ExchangeKey key;
    friend bool operator==(const StatisticsRequest&, const StatisticsRequest&) = default;
};

struct ExchangeStatistics {
    wire::ExchangeKey key;
    std::uint32_t config_time_s = 0;  ///< when the exchange's configuration took effect, UTC
    std::uint32_t due_time_ms = 0;    ///< until the next production, or the consumer's timeout
    ExchangeState state = ExchangeState::idle;
    std::uint32_t length = 0;
    std::uint32_t messages = 0;        ///< datagrams sent, or accepted
    std::uint32_t missed = 0;          ///< datagrams missed in sequence (consumed)
    std::uint32_t refresh_errors = 0;  ///< times the consumer timed out, or sends that failed
    friend bool operator==(const ExchangeStatistics&, const ExchangeStatistics&) = default;
};
inline constexpr std::size_t statistics_response_size = 48;

}  // namespace eip2mqtt::core::command
