#pragma once
/// Per-tag write rate limit: a token bucket refilled at `rate` per second holding at
/// most one second's worth (at least one write), so a UI may send a short burst but a runaway
/// client cannot hammer a controller's setpoint. Pure: time is passed in.

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::write {

class RateLimiter {
public:
    /// `rate` writes per second; 0 or less means no limit.
    explicit RateLimiter(double rate = 0);

    /// True when a write at `now` is within the limit (and takes its token).
    bool allow(MonoTime now);

private:
    double rate_;
    double capacity_;
    double tokens_;
    MonoTime last_{};
    bool started_ = false;
};

}  // namespace eip2mqtt::core::write
