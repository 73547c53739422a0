#include "eip2mqtt/core/exchange/status_grid.hpp"

namespace eip2mqtt::core::exchange {

void StatusGrid::set_phase(std::size_t index, std::size_t count) {
    phase_ = count == 0 ? std::chrono::nanoseconds{0}
                        : interval_ * static_cast<std::int64_t>(index % count) /
                              static_cast<std::int64_t>(count);
}

void StatusGrid::start(MonoTime origin, std::size_t index, std::size_t count) {
    set_phase(index, count);
    next_ = origin + std::chrono::duration_cast<MonoTime::duration>(phase_);
    // The grid is the points next_ + k * interval_: its phase, as reported_off_grid reads it.
    phase_ = next_.time_since_epoch() % interval_;
}

void StatusGrid::reported_on_grid(MonoTime now) {
    if (next_ == MonoTime{}) {
        // The first report: onto the grid from here.
        reported_off_grid(now);
        return;
    }
    // The next point of the grid after `now`: after a stall of the loop, the exchanges do not
    // all fall into one tick for good.
    next_ += (now - next_) / interval_ * interval_ + interval_;
}

void StatusGrid::reported_off_grid(MonoTime now) {
    // The first point phase_ + k * interval_ (k whole) at or after now + interval_.
    const auto earliest = (now + interval_).time_since_epoch() - phase_;
    auto k = earliest / interval_;
    if (k * interval_ < earliest) ++k;
    next_ = MonoTime{} + std::chrono::duration_cast<MonoTime::duration>(phase_ + k * interval_);
}

}  // namespace eip2mqtt::core::exchange
