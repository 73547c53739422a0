#pragma once
/// Drives every produced exchange from one timer on the loop: a timer per exchange cost one
/// wake-up and one sendto per datagram, more than the loop could keep up with at a thousand
/// exchanges of 100 Hz (docs/decisions/0005). At each wake-up the exchanges due (in the
/// current slot, see ProductionQueue) produce their datagrams, and all of them leave with one
/// sendmmsg. Then
/// each exchange does its bookkeeping (counters, `_status`, echo, persistence, write results).
/// The scheduler knows an exchange only as a Producible: what it needs to send it.
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/exchange/production_queue.hpp"
#include "eip2mqtt/core/exchange/production_schedule.hpp"
#include "eip2mqtt/core/exchange/sampling_clock.hpp"

namespace eip2mqtt::app {

/// An exchange as the scheduler drives it.
class Producible {
public:
    /// Builds the next datagram, stamped with `wall`; the bytes stay valid until the next call.
    virtual std::span<const std::byte> produce(core::WallTime wall) = 0;
    virtual const adapters::udp::Endpoint& destination() const = 0;
    /// Deadlines skipped because the loop fell behind by more than a period.
    virtual void count_skipped(std::size_t skipped) = 0;
    /// After the datagram of produce() was sent (or refused), once the whole batch has left.
    virtual void on_sent(bool sent, core::WallTime wall) = 0;

protected:
    ~Producible() = default;
};

class ProducerScheduler {
public:
    using Id = core::exchange::ProductionQueue::Id;
    /// Sends every datagram of a batch; `sent[i]` (resized to the batch) says whether datagram
    /// i left (adapters::udp::Sender::send_batch). Called once per wake-up, not per datagram.
    using SendBatch = std::function<void(std::span<const adapters::udp::OutgoingDatagram> batch,
                                         std::vector<bool>& sent)>;

    /// The batching slot (ProductionQueue): a datagram leaves less than this early. 250 us
    /// divides every whole-millisecond period, so batching adds no jitter, and fewer wake-ups
    /// keep the loop on time on a busy machine (docs/decisions/0005).
    static constexpr std::chrono::microseconds batch_slot{250};

    /// `sender` and `clock` (read at each wake-up: what is due, and the UTC time of each
    /// deadline) must outlive the scheduler. The timer itself waits on the steady clock.
    ProducerScheduler(boost::asio::any_io_executor loop, adapters::udp::Sender& sender,
                      const core::Clock& clock = adapters::clock::system_clock());
    /// Batches go to `send` (a test's recording fake).
    ProducerScheduler(boost::asio::any_io_executor loop, SendBatch send,
                      const core::Clock& clock = adapters::clock::system_clock());
    ~ProducerScheduler();
    ProducerScheduler(const ProducerScheduler&) = delete;
    ProducerScheduler& operator=(const ProducerScheduler&) = delete;

    /// Starts producing `producer` on `schedule`; returns its id. The producer must call
    /// remove() before it dies.
    Id add(Producible& producer, const core::exchange::ProductionSchedule& schedule);
    /// Stops producing and forgets the producer: nothing reaches it any more.
    void remove(Id id);
    /// Whether datagrams may leave at a wake-up: `role` (docs/redundancy.md), which must
    /// outlive the scheduler, says so. While it says no, the due deadlines pass and nothing is
    /// produced: no image takes its queued writes, no request id is spent. Unset: always.
    void set_role(const redundancy::UnitRole& role) { role_ = &role; }

    /// The clock it reads, which its producers read too.
    const core::Clock& clock() const { return clock_; }

private:
    void arm();
    void on_wake();

    boost::asio::steady_timer timer_;
    SendBatch send_;
    const core::Clock& clock_;
    core::exchange::ProductionQueue queue_{batch_slot};
    std::unordered_map<Id, Producible*> producers_;
    std::optional<core::MonoTime> armed_for_;
    core::exchange::SamplingClock sampling_clock_;
    const redundancy::UnitRole* role_ = &redundancy::always_leads();
    // Reused at every wake-up, so a steady batch allocates nothing.
    std::vector<core::exchange::ProductionQueue::Due> due_;
    std::vector<Producible*> batch_producers_;
    std::vector<adapters::udp::OutgoingDatagram> batch_;
    std::vector<bool> sent_;
};

}  // namespace eip2mqtt::app
