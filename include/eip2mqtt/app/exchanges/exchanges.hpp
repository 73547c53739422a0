#pragma once
/// The running exchanges and what they need: the consumers with the DatagramRouter that feeds
/// them, the producers with the UDP sender, the ProducerScheduler and the ImagePersister (all
/// three made with the first produced exchange: a consume-only gateway opens one socket). Their
/// life cycle is here: apply() builds them from plans at start and on a reload, keeping what
/// did not change; tick(), republish() and stop() reach every one; stage() hands a write to the
/// producer its handle names.
///
/// Threading: the loop only. Time is passed in.

#include <boost/asio/any_io_executor.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/state/image_persister.hpp"
#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/app/exchanges/datagram_router.hpp"
#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

struct ExchangesOptions {
    adapters::udp::SenderOptions sender;  ///< the socket produced datagrams leave from
    std::uint16_t port = 18246;           ///< eip.port: a destination's port when it names none
    std::string state_dir;                ///< where produced images are saved
    /// This unit's role, asked whether produced exchanges may send now (ProducerScheduler),
    /// whose request ids to follow (DatagramRouter), and by each producer about its changed
    /// images and its answers (ExchangeProducer::set_role); must outlive the exchanges.
    redundancy::UnitRole* role = &redundancy::always_leads();
};

/// What apply() did, by exchange name, in the order of the plans (stopped: of the exchanges
/// before).
struct ApplyReport {
    std::vector<std::string> kept;
    std::vector<std::string> started;
    std::vector<std::string> stopped;
    std::size_t cleared_topics = 0;  ///< retained topics no running exchange uses any more
    /// Writes queued on stopped producers, answered `reloaded`: no datagram will carry them.
    std::size_t cancelled_writes = 0;
    /// The names of what was kept, changed, started and stopped, for the log (describe_diff).
    std::string changes;
};

class Exchanges {
public:
    /// `northbound`, `totals` and `clock` (which every exchange reads) must outlive the
    /// exchanges.
    Exchanges(boost::asio::any_io_executor loop, ExchangesOptions options, Northbound& northbound,
              ImageSaveTotals& totals, const core::Clock& clock = adapters::clock::system_clock());
    ~Exchanges();
    Exchanges(const Exchanges&) = delete;
    Exchanges& operator=(const Exchanges&) = delete;

    /// Runs the exchanges of `plans`: one whose plan is unchanged keeps running as it is, a
    /// changed or new one starts, a removed or changed one stops (its queued writes answered
    /// `reloaded`, its retained topics cleared when no new exchange uses them). The northbound
    /// learns the running set before a stopped exchange dies. Once started, new producers
    /// produce at once and new exchanges publish their state. Throws std::runtime_error for a
    /// destination that does not resolve, and std::system_error when the sending socket cannot
    /// be opened.
    ApplyReport apply(std::vector<core::plan::ExchangePlan> plans, core::MonoTime now,
                      core::WallTime wall);
    /// Starts producing, each producer at its own phase of its period.
    void start(core::MonoTime now);
    /// Stops producing; every save under way reaches the disk and reports its write results.
    /// Logs each exchange whose image is not saved.
    void stop();

    /// One datagram as read from `from` (DatagramRouter::route).
    void route(std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
               bool truncated, core::MonoTime now) {
        router_.route(bytes, from, truncated, now);
    }
    /// Timeouts, refresh, each one's `_status`, the drop log's summary; `refresh_scan` about
    /// once a second (ExchangeConsumer::on_tick).
    void tick(core::MonoTime now, core::WallTime wall, bool refresh_scan);
    /// Every exchange's retained state reported again (a reconnect, new publish settings).
    void republish(core::MonoTime now, core::WallTime wall);
    /// Queues `write` on the producer its handle names (ExchangeProducer::stage); refused when
    /// no running producer has that handle.
    std::optional<core::write::WriteRejection> stage(ExchangeWrite&& write, const WriteReply& reply,
                                                     core::MonoTime now);

    /// Whether the producer `write` names already produces every value it writes (false when
    /// no running producer has that handle): a pair's new leader settling a write its old
    /// leader left unanswered (WriteDispatcher::settle).
    bool holds(const ExchangeWrite& write) const;

    /// The running exchanges as the northbounds see them.
    ExchangeSet running() const;
    /// Their plans, consumers first (the order core::plan::diff_plans counts in).
    std::vector<const core::plan::ExchangePlan*> running_plans() const;
    std::span<const std::unique_ptr<ExchangeConsumer>> consumers() const { return consumers_; }
    std::span<const std::unique_ptr<ExchangeProducer>> producers() const { return producers_; }
    const DatagramCounters& datagram_counters() const { return router_.counters(); }

private:
    struct Built {
        std::vector<ExchangeConsumer*> consumers;
        std::vector<ExchangeProducer*> producers;
    };
    /// A new producer, opening the sending socket with the first one.
    std::unique_ptr<ExchangeProducer> make_producer(core::plan::ExchangePlan plan,
                                                    std::optional<ImageHandover> handover);
    /// Stopped producers' queued writes answered; returns how many.
    std::size_t cancel_stopped(std::span<const std::size_t> stopped, std::size_t consumer_count,
                               std::span<std::unique_ptr<ExchangeProducer>> old_producers);
    void start_built(const Built& built, core::MonoTime now, core::WallTime wall);

    boost::asio::any_io_executor loop_;
    ExchangesOptions options_;
    Northbound& northbound_;
    ImageSaveTotals& totals_;
    const core::Clock& clock_;
    adapters::state::ImageStore image_store_;
    std::unique_ptr<adapters::udp::Sender> sender_;
    std::unique_ptr<ProducerScheduler> scheduler_;                ///< with sender_
    std::unique_ptr<adapters::state::ImagePersister> persister_;  ///< with sender_
    std::vector<std::unique_ptr<ExchangeConsumer>> consumers_;
    DatagramRouter router_;
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    std::unordered_map<ProducerHandle, ExchangeProducer*> by_handle_;
    bool started_ = false;
};

}  // namespace eip2mqtt::app
