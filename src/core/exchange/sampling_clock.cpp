#include "eip2mqtt/core/exchange/sampling_clock.hpp"

#include <cassert>

namespace eip2mqtt::core::exchange {
namespace {

std::chrono::nanoseconds offset_of(MonoTime mono, WallTime wall) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(wall.time_since_epoch()) -
           std::chrono::duration_cast<std::chrono::nanoseconds>(mono.time_since_epoch());
}

}  // namespace

void SamplingClock::observe(MonoTime mono, WallTime wall) {
    const auto offset = offset_of(mono, wall);
    if (!offset_) {
        offset_ = offset;
        return;
    }
    const auto moved = offset - *offset_;
    if (moved > tolerance_ || moved < -tolerance_) {
        offset_ = offset;
        ++reanchors_;
    }
}

WallTime SamplingClock::to_wall(MonoTime t) const {
    assert(offset_);
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()) +
                    offset_.value_or(std::chrono::nanoseconds{0});
    return WallTime{std::chrono::duration_cast<WallTime::duration>(ns)};
}

}  // namespace eip2mqtt::core::exchange
