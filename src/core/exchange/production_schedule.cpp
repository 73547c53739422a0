#include "eip2mqtt/core/exchange/production_schedule.hpp"

#include <cassert>
#include <cstdint>

namespace eip2mqtt::core::exchange {

ProductionSchedule::ProductionSchedule(MonoTime start, std::chrono::nanoseconds period,
                                       std::size_t index, std::size_t count)
    : period_(period), deadline_(start) {
    assert(period > std::chrono::nanoseconds::zero());
    assert(count == 0 || index < count);
    // docs/protocol.md §5: spread the first sends of equal periods over the period. Signed
    // arithmetic: nanoseconds * size_t would turn the count unsigned.
    if (count > 0) {
        deadline_ += std::chrono::nanoseconds{period.count() * static_cast<std::int64_t>(index) /
                                              static_cast<std::int64_t>(count)};
    }
}

std::size_t ProductionSchedule::advance(MonoTime now) {
    // §5: absolute deadlines; the period is added to the previous deadline, never to `now`, so
    // a late send does not shift the ones after it.
    deadline_ += period_;
    if (now <= deadline_) return 0;
    // The send just made was more than a whole period late, so the next deadline has passed
    // too: skip every missed deadline rather than send a burst, keeping the phase. The
    // deadline left is the first one after `now`.
    const auto skipped = (now - deadline_) / period_ + 1;
    deadline_ += skipped * period_;
    return static_cast<std::size_t>(skipped);
}

}  // namespace eip2mqtt::core::exchange
