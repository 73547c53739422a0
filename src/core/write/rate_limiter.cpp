#include "eip2mqtt/core/write/rate_limiter.hpp"

#include <algorithm>
#include <chrono>

namespace eip2mqtt::core::write {

RateLimiter::RateLimiter(double rate)
    : rate_(rate), capacity_(std::max(1.0, rate)), tokens_(capacity_) {}

bool RateLimiter::allow(MonoTime now) {
    if (rate_ <= 0) return true;
    if (started_) {
        const double elapsed = std::chrono::duration<double>(now - last_).count();
        tokens_ = std::min(capacity_, tokens_ + std::max(0.0, elapsed) * rate_);
    }
    started_ = true;
    last_ = now;
    if (tokens_ < 1.0) return false;
    tokens_ -= 1.0;
    return true;
}

}  // namespace eip2mqtt::core::write
