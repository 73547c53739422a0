#pragma once
/// Paces what a consumed exchange reports of itself (its tags' quality, its state, its
/// `_status`) when that changes faster than the exchange's period: a stream that alternates
/// good and bad datagrams (a length fault, a producer clock that flips) would otherwise
/// republish every tag and the `_status` with each datagram.
///
/// Changes are reported at once while they are rare: a change and its return (a timeout, then
/// the datagram that ends it) go through together. Beyond that, reports are paced at one per
/// period (a token bucket of `burst` changes, refilled one per period): a change that comes
/// sooner is held, and when its time comes, what the exchange is in then is reported, once
/// (nothing, if it is back to what was reported). Over any time T, at most T / period + `burst`
/// reports, ending on what the exchange is in. Pure: time is passed in.

#include <chrono>
#include <optional>

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::exchange {

class ChangePacer {
public:
    /// Changes reported together at most, before the pace of one per period applies.
    static constexpr int burst = 2;

    /// `period`: the exchange's period; a zero or negative one reports every change at once.
    explicit ChangePacer(std::chrono::milliseconds period) : period_(period) {}

    /// What the exchange reports changed at `now`: it differs from what was last reported. True:
    /// report it now; false: it is held until next_due().
    bool on_change(MonoTime now);

    /// What the exchange reports is back to what was last reported: nothing is held any more.
    void on_revert() { holding_ = false; }

    /// True, once, when a held change is due at `now`: report the exchange as it is now.
    bool take_due(MonoTime now);

    /// Whether a change is held.
    bool holding() const { return holding_; }
    /// When a held change falls due; nullopt while none is held.
    std::optional<MonoTime> next_due() const;

private:
    /// The earliest time a report conforms to the pace (GCRA: the theoretical arrival time of
    /// the next report, less the burst's allowance).
    MonoTime earliest() const { return paced_ - period_ * (burst - 1); }
    void report(MonoTime now);

    std::chrono::milliseconds period_;
    MonoTime paced_{};  ///< theoretical time of the next report at one per period
    bool holding_ = false;
};

}  // namespace eip2mqtt::core::exchange
