#pragma once
/// When an exchange's periodic `_status` is due: once a second, at the exchange's own phase of
/// the second. Consumers that started together (100 exchanges in one configuration) would
/// otherwise all report in the same tick, a burst of retained publications ahead of the tag
/// values that arrive with it; a thousand producers reporting in one handler held the loop long
/// enough for every exchange to skip a deadline (see
/// docs/decisions/0003-status-on-a-grid-per-exchange.md).
///
/// A periodic report keeps to the grid (two of them are a second apart, less up to one tick of
/// lateness); a report made off the grid (a state change) pushes the next periodic one to the
/// first point of the grid at least a second later.

#include <chrono>
#include <cstddef>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class StatusGrid {
public:
    explicit StatusGrid(std::chrono::nanoseconds interval = std::chrono::seconds(1))
        : interval_(interval) {}

    /// Exchange `index` of `count` started together: its phase is index / count of the
    /// interval. Before any report, the first periodic one is due at once.
    void set_phase(std::size_t index, std::size_t count);
    /// The same for exchanges started at `origin` (producers, whose sends are spread over the
    /// period from there): the first periodic report is due at origin + index / count of the
    /// interval.
    void start(MonoTime origin, std::size_t index, std::size_t count);
    std::chrono::nanoseconds phase() const { return phase_; }

    bool due(MonoTime now) const { return now >= next_; }
    /// A periodic report was made at `now` (due(now) held).
    void reported_on_grid(MonoTime now);
    /// A report was made at `now` for another reason.
    void reported_off_grid(MonoTime now);
    MonoTime next() const { return next_; }

private:
    std::chrono::nanoseconds interval_;
    std::chrono::nanoseconds phase_{0};
    MonoTime next_{};  ///< the epoch: due at once
};

}  // namespace eip2mqtt::core::exchange
