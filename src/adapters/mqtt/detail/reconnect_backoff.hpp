#pragma once
/// The delay before each reconnection attempt while the broker is away: exponential backoff
/// (min, 2 x min, 4 x min... up to max) capped by the outage's age, so that a short outage is
/// noticed soon after the broker is back while a long one is still tried rarely:
///
///     delay = min(doubling, max(min_backoff, outage age / 4), max_backoff)
///
/// Pure doubling had reached 8 s after a 10-s outage (up to 9 s of silence once the broker was
/// back); capped by age / 4, the attempts come at least every quarter of the outage's age, so
/// the broker is found at most a quarter of the outage's length after it returned (2.5 s after
/// a 10-s outage), and an outage of two minutes or more is tried every max_backoff (30 s).
///
/// The outage begins at the first delay asked after construction or reset() (the first failed
/// attempt or the lost connection). Time is passed in.
///
/// Module-private (src/adapters/mqtt/detail); not thread-safe: the client's loop owns it.

#include <algorithm>
#include <chrono>
#include <optional>

namespace eip2mqtt::adapters::mqtt::detail {

class ReconnectBackoff {
public:
    using Clock = std::chrono::steady_clock;

    ReconnectBackoff(std::chrono::milliseconds min_backoff, std::chrono::milliseconds max_backoff)
        : min_(min_backoff), max_(std::max(min_backoff, max_backoff)), doubling_(min_backoff) {}

    /// The delay before the next attempt, asked at `now` (an attempt failed or the connection
    /// was lost).
    std::chrono::milliseconds next(Clock::time_point now) {
        if (!outage_since_) outage_since_ = now;
        const auto age =
            std::chrono::duration_cast<std::chrono::milliseconds>(now - *outage_since_);
        const auto cap = std::min(std::max(min_, age / 4), max_);
        const auto delay = std::min(doubling_, cap);
        doubling_ = std::min(doubling_ * 2, max_);
        return delay;
    }

    /// Connected: the next outage starts again from min_backoff.
    void reset() {
        outage_since_.reset();
        doubling_ = min_;
    }

private:
    std::chrono::milliseconds min_;
    std::chrono::milliseconds max_;
    std::chrono::milliseconds doubling_;  ///< the pure exponential delay of the next attempt
    std::optional<Clock::time_point> outage_since_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
