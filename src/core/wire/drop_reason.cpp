#include "eip2mqtt/core/wire/drop_reason.hpp"

namespace eip2mqtt::core::wire {

std::string_view to_string(DropReason reason) {
    switch (reason) {
        case DropReason::too_short:
            return "too_short";
        case DropReason::not_data_pdu:
            return "not_data_pdu";
        case DropReason::too_long:
            return "too_long";
        case DropReason::unknown_exchange:
            return "unknown_exchange";
        case DropReason::wrong_source:
            return "wrong_source";
        case DropReason::no_data:
            return "no_data";
        case DropReason::signature_mismatch:
            return "signature_mismatch";
        case DropReason::length_mismatch:
            return "length_mismatch";
        case DropReason::duplicate:
            return "duplicate";
        case DropReason::out_of_order:
            return "out_of_order";
    }
    return "unknown";
}

}  // namespace eip2mqtt::core::wire
