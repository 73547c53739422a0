#pragma once
/// The one rule for logging what may repeat (a bad datagram, a refused write, a broker that
/// stays away): count every occurrence, log the first, then at most one summary per interval
/// with the count since the last line. A summary is due with the next occurrence once the
/// interval has passed, or from flush() on a periodic tick, so a flood that stops is summarised
/// all the same. Pure: time is passed in, and the caller writes the line.

#include <chrono>
#include <cstdint>
#include <optional>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core {

class ThrottledLog {
public:
    /// The interval of every throttled log of the gateway.
    static constexpr std::chrono::seconds default_interval{60};

    explicit ThrottledLog(std::chrono::seconds interval = default_interval) : interval_(interval) {}

    /// Records one occurrence at `now`. Returns how many occurrences the line to write now
    /// covers (this one included: 1 for the first), or 0 when no line is due.
    std::uint64_t record(MonoTime now) {
        ++pending_;
        return due(now) ? take(now) : 0;
    }

    /// The occurrences not written yet, when the last line is at least an interval old (a line
    /// is then due for them); 0 otherwise.
    std::uint64_t flush(MonoTime now) {
        return pending_ > 0 && logged_at_ && due(now) ? take(now) : 0;
    }

    /// Forgets the history: the next occurrence is logged as a first one (e.g. after the
    /// condition cleared: connected again).
    void reset() {
        pending_ = 0;
        logged_at_.reset();
    }

    std::chrono::seconds interval() const { return interval_; }

private:
    bool due(MonoTime now) const { return !logged_at_ || now - *logged_at_ >= interval_; }
    std::uint64_t take(MonoTime now) {
        const auto count = pending_;
        pending_ = 0;
        logged_at_ = now;
        return count;
    }

    std::chrono::seconds interval_;
    std::optional<MonoTime> logged_at_;
    std::uint64_t pending_ = 0;
};

}  // namespace eip2mqtt::core
