#pragma once
/// The one way the app reads time: monotonic time for timers, deadlines and rates, wall time
/// for the timestamps it publishes. A part that reads the time itself takes a `const Clock&`,
/// so that its test passes a fake (tests/support/fakes/fake_clock.hpp) and asserts exact
/// times; a part that is handed `now` by its caller needs none.
///
/// Threading: SystemClock is stateless and may be read from any thread.

#include <cstdint>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

class Clock {
public:
    virtual core::MonoTime monotonic() const = 0;
    virtual core::WallTime wall() const = 0;

    /// Wall time in whole milliseconds since 1970 UTC, as Sparkplug and the payloads write it.
    std::int64_t wall_ms() const;

protected:
    Clock() = default;
    ~Clock() = default;
    Clock(const Clock&) = default;
    Clock& operator=(const Clock&) = default;
};

/// The system's steady and system clocks.
class SystemClock final : public Clock {
public:
    core::MonoTime monotonic() const override;
    core::WallTime wall() const override;
};

/// The process's one SystemClock.
const Clock& system_clock();

}  // namespace eip2mqtt::app
