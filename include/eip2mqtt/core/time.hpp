#pragma once
/// Time as the core sees it: always passed in, never read from a clock, so that timeouts and
/// deadlines are tested by passing times rather than sleeping.

#include <chrono>
#include <cstdint>

namespace eip2mqtt::core {

/// Monotonic time for timers, timeouts and rates.
using MonoTime = std::chrono::steady_clock::time_point;
/// Wall-clock time for payload timestamps.
using WallTime = std::chrono::system_clock::time_point;

/// A wall time as the protocol writes it (a datagram's header, a command's answer): whole
/// seconds since 1970 UTC, and the nanoseconds past them, each 32 bits.
struct WireTime {
    std::uint32_t seconds = 0;
    std::uint32_t nanoseconds = 0;
};

constexpr WireTime wire_time(WallTime wall) {
    const auto since_epoch = wall.time_since_epoch();
    const auto seconds = std::chrono::floor<std::chrono::seconds>(since_epoch);
    return {
        static_cast<std::uint32_t>(seconds.count()),
        static_cast<std::uint32_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(since_epoch - seconds).count())};
}

/// A wall time as the payloads carry it: milliseconds since 1970 UTC.
constexpr std::int64_t to_ms(WallTime wall) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count();
}

}  // namespace eip2mqtt::core
