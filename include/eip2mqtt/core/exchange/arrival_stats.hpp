#pragma once
/// Arrival statistics of one exchange: how many datagrams came, how far apart on average, how
/// regularly, and how many per second lately. Pure: the caller passes the arrival times.
///
/// Jitter is the RFC 3550 §6.4.1 estimator applied to inter-arrival periods: for each period I
/// after the first, D = I - reference and J += (|D| - J) / 16. The reference is the expected
/// period when the constructor is given one (the producer's configured period, so a producer
/// that sends regularly but at the wrong rate shows as jittery), otherwise the running mean
/// period before I. A smoothed |D| needs no history, reacts within ~16 samples, and is what
/// network engineers read as "jitter"; a windowed standard deviation would need every sample of
/// the window kept.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "eip2mqtt/core/ring.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class ArrivalStats {
public:
    using Seconds = std::chrono::duration<double>;

    /// `expected_period`: the reference of the jitter (nullopt: the running mean). `window`:
    /// the span rate() counts over; must be positive.
    explicit ArrivalStats(std::optional<std::chrono::nanoseconds> expected_period = std::nullopt,
                          std::chrono::nanoseconds window = std::chrono::seconds(1));

    /// Records one arrival. Times are expected not to go backwards; one that does counts as a
    /// period of zero.
    void on_arrival(MonoTime now);

    /// Arrivals since construction.
    std::uint64_t count() const { return count_; }
    /// Mean inter-arrival period since the first arrival; nullopt before the second.
    std::optional<Seconds> mean_period() const;
    /// Smoothed |period - reference| (see above); zero until there is a difference to measure.
    Seconds jitter() const { return Seconds(jitter_s_); }
    /// Arrivals in the window (now - window, now], per second of window. Arrivals older than
    /// the window are forgotten by on_arrival; at most `max_window_arrivals` are kept, beyond
    /// which the rate is taken over the span the kept arrivals cover.
    double rate(MonoTime now) const;
    /// Time of the last arrival; nullopt before the first.
    std::optional<MonoTime> last_arrival() const;

    std::optional<std::chrono::nanoseconds> expected_period() const { return expected_; }
    std::chrono::nanoseconds window() const { return window_; }

    static constexpr std::size_t max_window_arrivals = 65536;

private:
    std::optional<std::chrono::nanoseconds> expected_;
    std::chrono::nanoseconds window_;
    std::uint64_t count_ = 0;
    MonoTime first_{};
    MonoTime last_{};
    double jitter_s_ = 0.0;
    Ring<MonoTime> recent_;  ///< arrivals within the window, oldest first
};

}  // namespace eip2mqtt::core::exchange
