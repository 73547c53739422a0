#pragma once
/// The loop's tick: every 10 ms, the times of the tick (TickTimes) handed to the gateway's
/// modules, the scan of what is counted in whole seconds flagged once a second, and the loop's
/// holds watched (LoopWatch) around it.
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <functional>

#include "eip2mqtt/app/health/loop_watch.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app {

class TickTimer {
public:
    /// How often timeouts and `_status` throttling are checked: a tenth of the shortest
    /// default timeout in practice, and cheap (one comparison per exchange).
    static constexpr std::chrono::milliseconds interval{10};
    /// refresh_s is counted in seconds, so the tags are scanned for it once a second.
    static constexpr std::chrono::seconds refresh_scan_interval{1};

    using OnTick = std::function<void(const TickTimes& times)>;

    TickTimer(boost::asio::any_io_executor loop, const core::Clock& clock);

    /// Ticks from now on, each calling `on_tick`, the first scan a second after `now`.
    void start(core::MonoTime now, OnTick on_tick);
    /// No tick from now on, even when called from one.
    void cancel() {
        ticking_ = false;
        timer_.cancel();
    }

private:
    void schedule();
    /// The times of the tick that runs now.
    TickTimes times();

    const core::Clock& clock_;
    boost::asio::steady_timer timer_;
    LoopWatch watch_;
    OnTick on_tick_;
    core::MonoTime last_refresh_scan_{};
    bool ticking_ = false;
};

}  // namespace eip2mqtt::app
