#pragma once
/// The command responder's rate limit per requester address (docs/protocol.md §9.7): one token
/// bucket per source (write::RateLimiter), so that one requester, or one forged source, spends
/// only its own share. At most `max_sources` buckets are kept: past that, every bucket is
/// dropped and each source starts again full, which the overall limits still bound. Pure: time
/// is passed in.

#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/rate_limiter.hpp"

namespace eip2mqtt::core::command {

class SourceLimiter {
public:
    /// `rate` requests per second per source; 0 means no limit.
    explicit SourceLimiter(std::uint32_t rate = 0, std::size_t max_sources = 4096)
        : rate_(rate), max_sources_(max_sources) {}

    /// True when a request from `address` at `now` is within its source's limit (and takes its
    /// token).
    bool allow(std::uint32_t address, MonoTime now);

    std::uint32_t rate() const { return rate_; }
    std::size_t sources() const { return buckets_.size(); }

private:
    std::uint32_t rate_;
    std::size_t max_sources_;
    std::unordered_map<std::uint32_t, write::RateLimiter> buckets_;
};

}  // namespace eip2mqtt::core::command
