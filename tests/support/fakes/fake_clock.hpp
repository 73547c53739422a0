#pragma once
// A fake Clock (how the app reads time): both times stand still until the test sets or advances
// them, so a test asserts exact times and never waits for the real clock. One thread.

#include <chrono>

#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::test {

/// Starts a day into the monotonic clock, as a gateway's does, at 2026-01-01T00:00:00Z.
class FakeClock final : public core::Clock {
public:
    FakeClock() = default;
    explicit FakeClock(core::WallTime wall) : wall_(wall) {}

    core::MonoTime monotonic() const override { return monotonic_; }
    core::WallTime wall() const override { return wall_; }

    /// Moves both clocks on together, as time passing does.
    void advance(std::chrono::nanoseconds by) {
        monotonic_ += by;
        wall_ += std::chrono::duration_cast<core::WallTime::duration>(by);
    }
    void set_monotonic(core::MonoTime at) { monotonic_ = at; }
    /// Steps the wall clock alone, as an NTP correction or an operator does.
    void set_wall(core::WallTime at) { wall_ = at; }

private:
    core::MonoTime monotonic_ = core::MonoTime{} + std::chrono::hours(24);
    core::WallTime wall_ = core::WallTime{} + std::chrono::seconds(1767225600);
};

}  // namespace eip2mqtt::test
