#pragma once
/// The real clock: the system's steady and system clocks, the only reader of them.
///
/// Threading: SystemClock is stateless and may be read from any thread.

#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::adapters::clock {

class SystemClock final : public core::Clock {
public:
    core::MonoTime monotonic() const override;
    core::WallTime wall() const override;
};

/// The process's one SystemClock.
const core::Clock& system_clock();

}  // namespace eip2mqtt::adapters::clock
