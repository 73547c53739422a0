#pragma once
/// The one way the app and the adapters read time: monotonic time for timers, deadlines and
/// rates, wall time for the timestamps they publish. A part that reads the time itself takes a
/// `const Clock&`, so that its test passes a fake (tests/support/fakes/fake_clock.hpp) and
/// asserts exact times; a part that is handed `now` by its caller needs none. The core only
/// declares it: the real clock is an adapter (adapters/clock/system_clock.hpp).

#include <chrono>
#include <cstdint>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core {

class Clock {
public:
    virtual MonoTime monotonic() const = 0;
    virtual WallTime wall() const = 0;

    /// Wall time in whole milliseconds since 1970 UTC, as Sparkplug and the payloads write it.
    std::int64_t wall_ms() const {
        return std::chrono::duration_cast<std::chrono::milliseconds>(wall().time_since_epoch())
            .count();
    }

protected:
    Clock() = default;
    ~Clock() = default;
    Clock(const Clock&) = default;
    Clock& operator=(const Clock&) = default;
};

}  // namespace eip2mqtt::core
