#pragma once
/// Logging the changes of a consumed exchange's state (stale, ok again, a length or signature
/// mismatch, its producer's clock) without flooding: each change has its line while they are
/// few, but an exchange that flaps (a stream alternating good and bad datagrams) gets one
/// summary per interval instead of a line per datagram.
///
/// A change is logged on its own line unless `burst` lines were written within the interval
/// before it, or a summary was: it is then counted, and the summary of those counted (a
/// core::ThrottledLog) is written at once for the first, then at most once per interval, by the
/// next change or by flush() on the tick. Once an interval passes without a change, lines are
/// written one by one again. Pure: time is passed in, the caller writes the line.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class ChangeLog {
public:
    /// Changes logged one by one within an interval, before the summary takes over.
    static constexpr std::size_t burst = 4;

    explicit ChangeLog(std::chrono::seconds interval = ThrottledLog::default_interval)
        : summary_(interval) {}

    /// How a change at `now` is logged.
    struct Line {
        bool single = false;        ///< its own line, as usual
        std::uint64_t summary = 0;  ///< else, when not 0: a summary of this many changes
    };
    Line on_change(MonoTime now);

    /// The changes counted and not logged yet, once their summary is due; 0 otherwise.
    std::uint64_t flush(MonoTime now) { return summary_.flush(now); }

    std::chrono::seconds interval() const { return summary_.interval(); }

private:
    bool summarising(MonoTime now) const;

    std::array<std::optional<MonoTime>, burst> singles_{};  ///< the last lines, oldest first
    ThrottledLog summary_;
    std::optional<MonoTime> summarised_at_;  ///< the last change counted into the summary
};

}  // namespace eip2mqtt::core::exchange
