#pragma once
/// The wait before the next connection attempt, on the loop: the ReconnectBackoff's delay,
/// asked at the client's clock's time, and the timer that runs it out.
///
/// Threading: the loop's.
///
/// Module-private (src/adapters/mqtt/detail).

#include <boost/asio/error.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/system/error_code.hpp>
#include <chrono>
#include <utility>

#include "adapters/mqtt/detail/loop_post.hpp"
#include "adapters/mqtt/detail/reconnect_backoff.hpp"
#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class ReconnectTimer {
public:
    /// `loop` and `options` (its backoff and clock) outlive it.
    ReconnectTimer(const LoopPost& loop, const ClientOptions& options)
        : loop_(loop),
          clock_(*options.clock),
          timer_(loop.executor()),
          backoff_(options.min_backoff, options.max_backoff) {}

    /// Runs `on_due()` on the loop after the next delay, unless cancel() comes first; returns
    /// the delay. Doubling, but never more than a quarter of the outage's age: a short outage
    /// is noticed soon after the broker is back (reconnect_backoff.hpp).
    template <class F>
    std::chrono::milliseconds schedule(F on_due) {
        const auto delay = backoff_.next(clock_.monotonic());
        timer_.expires_after(delay);
        timer_.async_wait(
            loop_.guarded([on_due = std::move(on_due)](boost::system::error_code ec) mutable {
                if (ec == boost::asio::error::operation_aborted) return;
                on_due();
            }));
        return delay;
    }
    void cancel() { timer_.cancel(); }
    /// Connected, or a session ended: the next outage starts from the shortest delay.
    void reset() { backoff_.reset(); }

private:
    const LoopPost& loop_;
    const core::Clock& clock_;
    boost::asio::steady_timer timer_;
    ReconnectBackoff backoff_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
