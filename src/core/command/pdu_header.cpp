#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::core::command {

std::optional<PduType> pdu_type_of(std::uint8_t byte) {
    switch (byte) {
        case 3:
        case 4:
        case 7:
        case 8:
        case 9:
        case 10:
        case 15:
        case 16:
        case 18:
        case 32:
        case 33:
        case 34:
        case 35:
        case 36:
        case 37:
            return static_cast<PduType>(byte);
        default:
            return std::nullopt;
    }
}

bool is_request(PduType type) { return response_type_of(type).has_value(); }

std::optional<PduType> response_type_of(PduType request) {
    switch (request) {
        case PduType::retrieve_config_request:
        case PduType::summary_request:
        case PduType::capabilities_request:
        case PduType::statistics_request:
        case PduType::read_request:
        case PduType::write_request:
        case PduType::masked_write_request:
            return static_cast<PduType>(static_cast<std::uint8_t>(request) + 1);
        default:
            return std::nullopt;
    }
}

std::string_view to_string(PduType type) {
    switch (type) {
        case PduType::retrieve_config_request:
            return "retrieve_config_request";
        case PduType::retrieve_config_response:
            return "retrieve_config_response";
        case PduType::summary_request:
            return "summary_request";
        case PduType::summary_response:
            return "summary_response";
        case PduType::capabilities_request:
            return "capabilities_request";
        case PduType::capabilities_response:
            return "capabilities_response";
        case PduType::statistics_request:
            return "statistics_request";
        case PduType::statistics_response:
            return "statistics_response";
        case PduType::nak:
            return "nak";
        case PduType::read_request:
            return "read_request";
        case PduType::read_response:
            return "read_response";
        case PduType::write_request:
            return "write_request";
        case PduType::write_response:
            return "write_response";
        case PduType::masked_write_request:
            return "masked_write_request";
        case PduType::masked_write_response:
            return "masked_write_response";
    }
    return "unknown";
}

PduHeader reply_header(const PduHeader& request, PduType response_type, std::uint8_t status) {
    PduHeader header;
    header.type = response_type;
    header.flag = request.flag;
    header.request_id = request.request_id;
    header.status = status;
    return header;
}

}  // namespace eip2mqtt::core::command
