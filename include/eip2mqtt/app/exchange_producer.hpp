#pragma once
/// One produced exchange at run time (issue #3): produces its datagram when the
/// ProducerScheduler says it is due (every period, against absolute deadlines), applies queued
/// writes between two productions, reports the produced values that changed (the echo) to the
/// Northbound, has the ImagePersister save the image when it changes, and answers each write
/// once the datagram carrying it has left and the image carrying it is saved.
///
/// Threading: the loop only.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/state/image_persister.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/app/northbound.hpp"
#include "eip2mqtt/app/producer_scheduler.hpp"
#include "eip2mqtt/app/write_reply.hpp"
#include "eip2mqtt/core/exchange/produced_image.hpp"
#include "eip2mqtt/core/exchange/production_schedule.hpp"
#include "eip2mqtt/core/exchange/status_grid.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/write/rate_limiter.hpp"
#include "eip2mqtt/core/write/write_request.hpp"

namespace eip2mqtt::app {

struct ProducerCounters {
    std::uint64_t sent = 0;
    std::uint64_t send_errors = 0;
    std::uint64_t skipped_deadlines = 0;  ///< periods lost because the loop fell behind
    std::uint64_t writes_applied = 0;
    std::uint64_t persist_failures = 0;
};

class ExchangeProducer : public Producible {
public:
    /// The image is restored through `persister` when a file of the same layout exists.
    /// `scheduler`, `persister` and `northbound` must outlive the producer.
    ExchangeProducer(core::plan::ExchangePlan plan, adapters::udp::Endpoint destination,
                     ProducerScheduler& scheduler, adapters::state::ImagePersister& persister,
                     Northbound& northbound);
    ~ExchangeProducer();
    ExchangeProducer(const ExchangeProducer&) = delete;
    ExchangeProducer& operator=(const ExchangeProducer&) = delete;

    /// Starts producing; the first send is at start + period * index / count.
    void start(core::MonoTime start, std::size_t index, std::size_t count);
    /// Stops producing; saves under way still report their write results.
    void stop();
    /// For a stopped producer about to be destroyed (a reload changed or removed its
    /// exchange): answers every write still queued, which no datagram will ever carry, with
    /// `error` and forgets it; returns how many. Writes already carried by
    /// a sent datagram are not touched: they wait for their save, so flush the persister
    /// before destroying the producer, and they get `{"ok":true}`.
    std::size_t cancel_queued_writes(std::string_view error);

    /// Queues a validated write; its result is reported after the datagram carrying it is
    /// sent. Fails with rate_limited when a tag is written more often than its
    /// `max_writes_per_s`, and with queue_full when the queue is full.
    std::optional<core::write::WriteRejection> stage(std::vector<core::write::TagWrite> writes,
                                                     WriteReply reply, core::MonoTime now);

    /// The status at most once a second while its counters move (docs/mqtt-api.md).
    void on_tick(core::MonoTime now);

    /// Reports every tag's value and the status again (after a reconnect).
    void republish(core::WallTime wall);

    // --- Producible: called by the ProducerScheduler -------------------------------------
    /// Builds the next datagram (staged writes applied, header stamped with `wall`); the bytes
    /// stay valid until the next call.
    std::span<const std::byte> produce(core::WallTime wall) override;
    const adapters::udp::Endpoint& destination() const override { return destination_; }
    void count_skipped(std::size_t skipped) override { counters_.skipped_deadlines += skipped; }
    /// Counters, `paused`, echo, and the save whose completion reports the results of the
    /// writes the datagram carried.
    void on_sent(bool sent, core::WallTime wall) override;

    const core::plan::ExchangePlan& plan() const { return *plan_; }
    const ProducerCounters& counters() const { return counters_; }
    /// True while sends fail (the status says paused).
    bool paused() const { return failing_; }
    const core::exchange::ProducedImage& image() const { return image_; }
    /// When the last datagram left; nullopt before the first.
    std::optional<core::WallTime> last_sent() const { return last_sent_; }
    /// When this exchange's configuration took effect (the producer was made).
    core::WallTime configured_at() const { return configured_at_; }

private:
    /// The image save asked by on_sent() is done: reports the results of `write_ids`.
    void on_saved(bool ok, const std::vector<std::uint64_t>& write_ids);
    void report_echo(core::WallTime wall, bool all);
    void report_status();
    void report_results(const std::vector<std::uint64_t>& write_ids);

    /// Shared with the saves under way, which may outlive this producer (reload).
    std::shared_ptr<const core::plan::ExchangePlan> plan_;
    adapters::udp::Endpoint destination_;
    ProducerScheduler& scheduler_;
    std::optional<ProducerScheduler::Id> id_;  ///< set by start(), reset by stop()
    adapters::state::ImagePersister& persister_;
    adapters::state::ImagePersister::Key persist_key_;
    std::size_t saves_in_flight_ = 0;
    Northbound& northbound_;
    core::exchange::ProducedImage image_;
    std::vector<std::byte> datagram_;
    std::vector<std::byte> echoed_;  ///< data bytes as last reported
    std::vector<std::uint64_t> carried_;
    std::unordered_map<std::uint64_t, WriteReply> replies_;
    std::vector<core::write::RateLimiter> limiters_;  ///< one per tag
    core::exchange::StatusGrid status_grid_;          ///< `_status`: phase set by start()
    std::uint64_t last_status_sent_ = 0;
    std::uint64_t next_write_id_ = 1;
    ProducerCounters counters_;
    bool failing_ = false;  ///< the last send failed: the status says paused
    std::optional<core::WallTime> last_sent_;
    core::WallTime configured_at_ = std::chrono::system_clock::now();
};

}  // namespace eip2mqtt::app
