#pragma once
/// When each produced exchange is due (docs/protocol.md §5): absolute deadlines, so a period never
/// drifts however late a send was, and first sends spread over the period so that many
/// exchanges with equal periods never leave in one burst. Pure: time is passed in.

#include <chrono>
#include <cstddef>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class ProductionSchedule {
public:
    /// The `index`-th of `count` exchanges sharing a start time: its first deadline is
    /// start + period * index / count.
    ProductionSchedule(MonoTime start, std::chrono::nanoseconds period, std::size_t index,
                       std::size_t count);

    MonoTime deadline() const { return deadline_; }

    /// Moves to the next deadline after a send. When the loop fell behind by more than a whole
    /// period (a stalled machine), skips the missed deadlines rather than sending a burst,
    /// keeping the phase: the next deadline is then the first one after `now`. Returns how many
    /// deadlines were skipped (0 when the send was less than a period late).
    std::size_t advance(MonoTime now);

private:
    std::chrono::nanoseconds period_;
    MonoTime deadline_;
};

}  // namespace eip2mqtt::core::exchange
