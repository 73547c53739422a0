#include "eip2mqtt/core/config/reload_slice.hpp"

#include <algorithm>

namespace eip2mqtt::core::config {

std::size_t slice_units(std::size_t units, const PublishQueueRoom& room) {
    if (!room.connected) return units;
    // A capacity of one still lets one publication through at a time.
    const auto half = std::max<std::size_t>(room.capacity / 2, 1);
    return room.queued >= half ? 0 : std::min(units, half - room.queued);
}

}  // namespace eip2mqtt::core::config
