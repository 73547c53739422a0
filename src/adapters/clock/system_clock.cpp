#include "eip2mqtt/adapters/clock/system_clock.hpp"

#include <chrono>

namespace eip2mqtt::adapters::clock {

core::MonoTime SystemClock::monotonic() const { return std::chrono::steady_clock::now(); }

core::WallTime SystemClock::wall() const { return std::chrono::system_clock::now(); }

const core::Clock& system_clock() {
    static const SystemClock clock;
    return clock;
}

}  // namespace eip2mqtt::adapters::clock
