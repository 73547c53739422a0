#include "eip2mqtt/app/health/tick_timer.hpp"

namespace eip2mqtt::app {

TickTimer::TickTimer(boost::asio::any_io_executor loop, const core::Clock& clock)
    : clock_(clock), timer_(std::move(loop)) {}

void TickTimer::start(core::MonoTime now, OnTick on_tick) {
    on_tick_ = std::move(on_tick);
    last_refresh_scan_ = now;
    ticking_ = true;
    schedule();
}

void TickTimer::schedule() {
    timer_.expires_after(interval);
    timer_.async_wait([this](const boost::system::error_code& error) {
        if (error || !ticking_) return;
        watch_.on_tick(timer_.expiry(), clock_.monotonic());
        const auto tick = times();
        on_tick_(tick);
        watch_.flush(tick.now);
        if (ticking_) schedule();
    });
}

TickTimes TickTimer::times() {
    TickTimes tick{clock_.monotonic(), clock_.wall()};
    if (tick.now - last_refresh_scan_ >= refresh_scan_interval) {
        tick.refresh_scan = true;
        last_refresh_scan_ = tick.now;
    }
    return tick;
}

}  // namespace eip2mqtt::app
