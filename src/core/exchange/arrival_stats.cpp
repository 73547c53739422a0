#include "eip2mqtt/core/exchange/arrival_stats.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace eip2mqtt::core::exchange {

ArrivalStats::ArrivalStats(std::optional<std::chrono::nanoseconds> expected_period,
                           std::chrono::nanoseconds window)
    : expected_(expected_period), window_(window) {
    assert(window_.count() > 0);
}

void ArrivalStats::on_arrival(MonoTime now) {
    // A time that goes backwards counts as a period of zero, which also keeps recent_ sorted.
    const MonoTime at = count_ == 0 ? now : std::max(now, last_);
    if (count_ == 0) {
        first_ = at;
    } else {
        // The reference is taken before this period joins the mean.
        const auto mean_before = mean_period();
        const auto period = Seconds(at - last_).count();
        std::optional<double> reference;
        if (expected_) {
            reference = Seconds(*expected_).count();
        } else if (mean_before) {
            reference = mean_before->count();
        }
        if (reference) {
            // RFC 3550 §6.4.1: J += (|D| - J) / 16.
            jitter_s_ += (std::abs(period - *reference) - jitter_s_) / 16.0;
        }
    }
    last_ = at;
    ++count_;

    // Forgotten before the push, so that the ring never needs a slot beyond the cap.
    while (!recent_.empty() && recent_.front() <= last_ - window_) recent_.pop_front();
    while (recent_.size() >= max_window_arrivals) recent_.pop_front();
    recent_.push_back(at);
}

std::optional<ArrivalStats::Seconds> ArrivalStats::mean_period() const {
    if (count_ < 2) return std::nullopt;
    return Seconds(last_ - first_) / static_cast<double>(count_ - 1);
}

namespace {

/// Index of the first of `times` (sorted) after `t`, from `first`: std::upper_bound by index
/// (a Ring has no iterators, and std::ranges::upper_bound over views::iota does not compile
/// with the fuzz build's clang 14 and libstdc++ 12).
std::size_t first_after(const Ring<MonoTime>& times, std::size_t first, MonoTime t) {
    std::size_t count = times.size() - first;
    while (count > 0) {
        const std::size_t half = count / 2;
        if (times[first + half] <= t) {
            first += half + 1;
            count -= half + 1;
        } else {
            count = half;
        }
    }
    return first;
}

}  // namespace

double ArrivalStats::rate(MonoTime now) const {
    const auto from = now - window_;
    const std::size_t first_in = first_after(recent_, 0, from);
    const std::size_t last_in = first_after(recent_, first_in, now);
    const auto n = static_cast<double>(last_in - first_in);
    if (recent_.size() == max_window_arrivals && first_in == 0 && n > 1) {
        // The cap dropped arrivals still inside the window: rate over what is kept.
        const auto span = Seconds(now - recent_[first_in]).count();
        if (span > 0) return n / span;
    }
    return n / Seconds(window_).count();
}

std::optional<MonoTime> ArrivalStats::last_arrival() const {
    if (count_ == 0) return std::nullopt;
    return last_;
}

}  // namespace eip2mqtt::core::exchange
