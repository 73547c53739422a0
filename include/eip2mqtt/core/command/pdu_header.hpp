#pragma once
/// The command protocol on UDP 7937 (docs/protocol.md §9): PDU types and the 8-byte header that
/// starts every request and response.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace eip2mqtt::core::command {

inline constexpr std::uint16_t default_port = 7937;
inline constexpr std::size_t header_size = 8;
/// The largest PDU either side sends or accepts (§9.1).
inline constexpr std::size_t max_pdu_size = 1400;
inline constexpr std::uint8_t protocol_version = 1;

/// Every PDU type of §9.2. Requests are odd except Read, Write and Masked Write (32, 34, 36);
/// each response is its request's type + 1.
enum class PduType : std::uint8_t {
    retrieve_config_request = 3,
    retrieve_config_response = 4,
    summary_request = 7,
    summary_response = 8,
    capabilities_request = 9,
    capabilities_response = 10,
    statistics_request = 15,
    statistics_response = 16,
    nak = 18,
    read_request = 32,
    read_response = 33,
    write_request = 34,
    write_response = 35,
    masked_write_request = 36,
    masked_write_response = 37,
};

/// The PDU type of a byte, if it is one of §9.2.
std::optional<PduType> pdu_type_of(std::uint8_t byte);
bool is_request(PduType type);
/// The response to a request type; a response or a NAK has none.
std::optional<PduType> response_type_of(PduType request);
/// snake_case name, as used in metrics and logs (`read_request`).
std::string_view to_string(PduType type);

/// The header of every PDU. `length` is the whole PDU's size in bytes, header included.
struct PduHeader {
    PduType type = PduType::capabilities_request;
    std::uint8_t flag = 0;         ///< the requester's; a response echoes it
    std::uint16_t request_id = 0;  ///< the requester's; a response echoes it
    std::uint8_t version = protocol_version;
    std::uint8_t status = 0;  ///< 0 in requests; a CommandStatus in responses
    std::uint16_t length = 0;
};

/// The header of the response to `request`: its flag and request id, the response's type.
PduHeader reply_header(const PduHeader& request, PduType response_type, std::uint8_t status = 0);

}  // namespace eip2mqtt::core::command
