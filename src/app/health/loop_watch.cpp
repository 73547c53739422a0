#include "eip2mqtt/app/health/loop_watch.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace eip2mqtt::app {

std::chrono::milliseconds LoopWatch::on_tick(core::MonoTime due, core::MonoTime now) {
    const auto late = std::chrono::duration_cast<std::chrono::milliseconds>(now - due);
    if (late < threshold) return late;
    ++holds_;
    longest_ = std::max(longest_, late);
    if (const auto count = log_.record(now)) emit(count);
    return late;
}

void LoopWatch::flush(core::MonoTime now) {
    if (const auto count = log_.flush(now)) emit(count);
}

void LoopWatch::emit(std::uint64_t count) {
    if (count == 1) {
        spdlog::warn(
            "loop: held {} ms (an overloaded machine, a stopped process or a long handler): "
            "every timer (staleness checks, production, the role's renewals) ran that late",
            longest_.count());
    } else {
        spdlog::warn("loop: held {} more time(s), the longest {} ms", count, longest_.count());
    }
    longest_ = std::chrono::milliseconds{0};
}

}  // namespace eip2mqtt::app
