#include "eip2mqtt/core/command/decode_error.hpp"

namespace eip2mqtt::core::command {

// docs/protocol.md §9.5: the codes are eip2mqtt's; the manual defines none.
std::optional<std::uint16_t> nak_code(DecodeError error) {
    switch (error) {
        case DecodeError::oversized:
            return 1;
        case DecodeError::wrong_version:
            return 2;
        case DecodeError::wrong_length:
            return 3;
        case DecodeError::unknown_type:
            return 4;
        case DecodeError::truncated:
            return 5;
        case DecodeError::malformed:
            return 6;
        case DecodeError::no_header:
        case DecodeError::not_a_request:
        case DecodeError::not_a_response:
            return std::nullopt;
    }
    return std::nullopt;
}

std::optional<DecodeError> decode_error_of_nak_code(std::uint16_t code) {
    for (const auto error : all_decode_errors) {
        if (nak_code(error) == code) return error;
    }
    return std::nullopt;
}

}  // namespace eip2mqtt::core::command
