#include "eip2mqtt/core/command/command_status.hpp"

namespace eip2mqtt::core::command {

std::optional<CommandStatus> command_status_of(std::uint8_t byte) {
    if (byte >= command_status_names.size()) return std::nullopt;
    return static_cast<CommandStatus>(byte);
}

}  // namespace eip2mqtt::core::command
