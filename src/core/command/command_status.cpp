#include "eip2mqtt/core/command/command_status.hpp"

namespace eip2mqtt::core::command {

std::string_view to_string(CommandStatus status) {
    switch (status) {
        case CommandStatus::success:
            return "success";
        case CommandStatus::unknown_exchange:
            return "unknown_exchange";
        case CommandStatus::not_permitted:
            return "not_permitted";
        case CommandStatus::out_of_range:
            return "out_of_range";
        case CommandStatus::rejected:
            return "rejected";
        case CommandStatus::signature_mismatch:
            return "signature_mismatch";
        case CommandStatus::unsupported_address:
            return "unsupported_address";
        case CommandStatus::no_data:
            return "no_data";
        case CommandStatus::failed:
            return "failed";
    }
    return "unknown";
}

std::optional<CommandStatus> command_status_of(std::uint8_t byte) {
    if (byte > static_cast<std::uint8_t>(CommandStatus::failed)) return std::nullopt;
    return static_cast<CommandStatus>(byte);
}

}  // namespace eip2mqtt::core::command
