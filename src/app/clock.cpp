#include "eip2mqtt/app/clock.hpp"

#include <chrono>

namespace eip2mqtt::app {

std::int64_t Clock::wall_ms() const {
    return std::chrono::duration_cast<std::chrono::milliseconds>(wall().time_since_epoch()).count();
}

core::MonoTime SystemClock::monotonic() const { return std::chrono::steady_clock::now(); }

core::WallTime SystemClock::wall() const { return std::chrono::system_clock::now(); }

const Clock& system_clock() {
    static const SystemClock clock;
    return clock;
}

}  // namespace eip2mqtt::app
