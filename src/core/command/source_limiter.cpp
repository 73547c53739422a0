#include "eip2mqtt/core/command/source_limiter.hpp"

namespace eip2mqtt::core::command {

bool SourceLimiter::allow(std::uint32_t address, MonoTime now) {
    if (rate_ == 0) return true;
    auto found = buckets_.find(address);
    if (found == buckets_.end()) {
        // A flood of forged sources must not grow the table without bound.
        if (buckets_.size() >= max_sources_) buckets_.clear();
        found = buckets_.emplace(address, write::RateLimiter(rate_)).first;
    }
    return found->second.allow(now);
}

}  // namespace eip2mqtt::core::command
