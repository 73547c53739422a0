#pragma once
/// Says when the loop was held: a tick that runs far later than its timer asked means nothing
/// ran on the loop meanwhile (an overloaded machine, a process stopped, a long handler), so the
/// pair's lease, staleness and production were late by as much. The first hold is logged, then
/// at most one summary a minute (core::ThrottledLog); each with the longest hold since the last
/// line.
///
/// Threading: the loop only.

#include <chrono>
#include <cstdint>

#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

class LoopWatch {
public:
    /// A tick later than this is a hold: ten ticks.
    static constexpr std::chrono::milliseconds threshold{100};

    /// A tick ran at `now`, asked for at `due`. Returns how late it ran.
    std::chrono::milliseconds on_tick(core::MonoTime due, core::MonoTime now);
    /// The summary of holds not logged yet, when one is due.
    void flush(core::MonoTime now);

    std::uint64_t holds() const { return holds_; }

private:
    void emit(std::uint64_t count);

    core::ThrottledLog log_;
    std::uint64_t holds_ = 0;
    std::chrono::milliseconds longest_{0};  ///< since the last line
};

}  // namespace eip2mqtt::app
