// Client::stop in named steps: leave the loop, announce `offline`, flush, end the sender, say
// the will, disconnect. Runs on the stopping thread; the loop may no longer run.

#include <spdlog/spdlog.h>

#include <algorithm>

#include "adapters/mqtt/detail/client_impl.hpp"

namespace eip2mqtt::adapters::mqtt {

void Client::Impl::stop(std::chrono::milliseconds flush_timeout) {
    if (!sender_.begin_stop()) {
        return;
    }
    stop_loop_work();
    const auto deadline = options_.clock->monotonic() + flush_timeout;
    if (!connection_.link_alive()) {
        stop_disconnected();
        return;
    }
    auto last = connection_.publish_offline(deadline);
    // The sender keeps sending until the queue is flushed or the time is up.
    const std::size_t unsent = sender_.flush(deadline);
    sender_.end_thread();
    if (auto will = connection_.publish_last_will()) {
        last = std::move(will);
    }
    wait_for_last(last, deadline);
    if (unsent > 0) {
        spdlog::warn("{} stop: {} publications not confirmed within {} ms", options_.log_name,
                     unsent, flush_timeout.count());
    }
    connection_.disconnect();
}

void Client::Impl::stop_loop_work() {
    // Cancelled there if the loop still runs; nothing of the loop's is touched here.
    loop_.post([this] {
        connection_.on_stopped();
        sender_.cancel_hold();
    });
}

void Client::Impl::stop_disconnected() {
    const std::size_t lost = sender_.queued();
    sender_.end_thread();
    if (lost > 0) {
        spdlog::warn("{} stopping while disconnected: {} queued publications dropped",
                     options_.log_name, lost);
    }
    connection_.mark_disconnected();
}

void Client::Impl::wait_for_last(const ::mqtt::delivery_token_ptr& last,
                                 core::MonoTime deadline) const {
    if (!last) {
        return;
    }
    const auto left =
        std::max(core::MonoTime::duration::zero(), deadline - options_.clock->monotonic());
    try {
        last->wait_for(std::chrono::duration_cast<std::chrono::milliseconds>(left));
    } catch (const ::mqtt::exception&) {
    }
}

}  // namespace eip2mqtt::adapters::mqtt
