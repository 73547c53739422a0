#pragma once
/// Time as the core sees it: always passed in, never read from a clock, so that timeouts and
/// deadlines are tested by passing times rather than sleeping.

#include <chrono>

namespace eip2mqtt::core {

/// Monotonic time for timers, timeouts and rates.
using MonoTime = std::chrono::steady_clock::time_point;
/// Wall-clock time for payload timestamps.
using WallTime = std::chrono::system_clock::time_point;

}  // namespace eip2mqtt::core
