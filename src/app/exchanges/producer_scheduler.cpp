#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"

#include <utility>

namespace eip2mqtt::app {

ProducerScheduler::ProducerScheduler(boost::asio::any_io_executor loop,
                                     adapters::udp::Sender& sender, const core::Clock& clock)
    : ProducerScheduler(
          std::move(loop),
          [&sender](std::span<const adapters::udp::OutgoingDatagram> batch,
                    std::vector<bool>& sent) { sender.send_batch(batch, sent); },
          clock) {}

ProducerScheduler::ProducerScheduler(boost::asio::any_io_executor loop, SendBatch send,
                                     const core::Clock& clock)
    : timer_(std::move(loop)), send_(std::move(send)), clock_(clock) {}

ProducerScheduler::~ProducerScheduler() = default;

ProducerScheduler::Id ProducerScheduler::add(Producible& producer,
                                             const core::exchange::ProductionSchedule& schedule) {
    const auto id = queue_.add(schedule);
    producers_.emplace(id, &producer);
    if (!armed_for_ || queue_.next_wakeup() < *armed_for_) arm();
    return id;
}

void ProducerScheduler::remove(Id id) {
    // The timer may stay armed for the removed exchange's deadline: that wake-up finds
    // nothing due, or other exchanges, and arms for the next.
    queue_.remove(id);
    producers_.erase(id);
}

void ProducerScheduler::arm() {
    armed_for_ = queue_.next_wakeup();
    if (!armed_for_) {
        timer_.cancel();
        return;
    }
    // expires_at cancels the wait armed before: exactly one wait is live at a time, and an
    // aborted one returns without touching anything (the scheduler may be gone on stop).
    timer_.expires_at(*armed_for_);
    timer_.async_wait([this](const boost::system::error_code& error) {
        if (!error) on_wake();
    });
}

void ProducerScheduler::on_wake() {
    const auto now = clock_.monotonic();
    due_.clear();
    queue_.take_due(now, due_);
    // Asked at the moment of sending: a process resumed after SIGSTOP is fenced here, whatever
    // its timers did not run while it was stopped.
    if (!role_->may_produce(now)) due_.clear();
    // Each datagram carries the UTC time of the deadline it serves (SamplingClock), so that
    // its consumers see whole periods however late the loop woke.
    sampling_clock_.observe(now, clock_.wall());
    batch_producers_.clear();
    batch_.clear();
    for (const auto& due : due_) {
        auto* producer = producers_.at(due.id);
        producer->count_skipped(due.skipped);
        batch_producers_.push_back(producer);
        batch_.push_back(
            {producer->produce(sampling_clock_.to_wall(due.deadline)), producer->destination()});
    }
    if (!batch_.empty()) send_(batch_, sent_);
    // Bookkeeping only once every datagram has left, so that MQTT publications, echo and
    // persistence never delay a datagram of the same batch.
    for (std::size_t i = 0; i < batch_producers_.size(); ++i) {
        batch_producers_[i]->on_sent(sent_[i], sampling_clock_.to_wall(due_[i].deadline));
    }
    arm();
}

}  // namespace eip2mqtt::app
