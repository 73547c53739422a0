#include "eip2mqtt/core/redundancy/bd_seq.hpp"

namespace eip2mqtt::core::redundancy {

std::uint8_t next_session_bd_seq(std::optional<std::uint8_t> heard, std::uint8_t own_next) {
    // Sparkplug B 3.0: bdSeq runs 0-255, then 0 again.
    return heard ? static_cast<std::uint8_t>(*heard + 1) : own_next;
}

}  // namespace eip2mqtt::core::redundancy
