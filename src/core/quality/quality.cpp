#include "eip2mqtt/core/quality/quality.hpp"

namespace eip2mqtt::core::quality {

std::optional<Quality> quality_of(exchange::ConsumeState state) {
    using exchange::ConsumeState;
    switch (state) {
        case ConsumeState::waiting:
            return std::nullopt;
        case ConsumeState::ok:
            return Quality::good;
        case ConsumeState::stale:
            return Quality::stale;
        case ConsumeState::signature_mismatch:
        case ConsumeState::length_mismatch:
            return Quality::bad;
    }
    return Quality::bad;
}

}  // namespace eip2mqtt::core::quality
