#pragma once
/// One produced exchange at run time: produces its datagram when the
/// ProducerScheduler says it is due (every period, against absolute deadlines), applies queued
/// writes between two productions, reports the produced values that changed (the echo) to the
/// Northbound, has the ImagePersister save the image when it changes, and answers each write
/// once the datagram carrying it has left and the image carrying it is saved.
///
/// The image in memory is the truth, and what a restart produces is the image file: so nothing
/// is produced that is not saved, bar one case. While saves succeed, a write is produced first
/// and saved right after (its result waits for the save): the write costs no disk time on its
/// way to the wire. Once a save has failed, and until one succeeds (retried every second), each
/// write is saved before it may be produced, and refused (`not saved: …`) if that save fails.
/// The one case is the save that fails first: the writes it carried were sent already; they are
/// answered `saved: false`, and a restart before the next successful save produces the image
/// from before them. core::exchange::SaveThenAnswer holds these rules; the producer does the
/// saves and the answers it names.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/state/image_persister.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"
#include "eip2mqtt/app/exchanges/write_reply.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/exchange/produced_image.hpp"
#include "eip2mqtt/core/exchange/production_schedule.hpp"
#include "eip2mqtt/core/exchange/save_then_answer.hpp"
#include "eip2mqtt/core/exchange/status_grid.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/write/rate_limiter.hpp"
#include "eip2mqtt/core/write/write_counters.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app {

using core::write::ImageSaveTotals;

/// A producer's image, for the one that replaces it when a reload changes its exchange but
/// not its layout: the image in memory goes on, not what the file holds.
struct ImageHandover {
    std::vector<std::byte> data;
    std::shared_ptr<adapters::state::ImageFile> file;
};

class ExchangeProducer final : public Producible {
public:
    /// The image is `handover`'s when given, else restored through `persister` when a file of
    /// the same layout exists. `scheduler`, `persister`, `northbound` and `totals` must outlive
    /// the producer; it reads the scheduler's clock.
    ExchangeProducer(core::plan::ExchangePlan plan, adapters::udp::Endpoint destination,
                     ProducerScheduler& scheduler, adapters::state::ImagePersister& persister,
                     Northbound& northbound, ImageSaveTotals& totals,
                     std::optional<ImageHandover> handover = std::nullopt);
    ~ExchangeProducer();
    ExchangeProducer(const ExchangeProducer&) = delete;
    ExchangeProducer& operator=(const ExchangeProducer&) = delete;

    /// Starts producing; the first send is at start + period * index / count.
    void start(core::MonoTime start, std::size_t index, std::size_t count);
    /// Stops producing; saves under way still report their write results.
    void stop();
    /// For a stopped producer about to be destroyed (a reload changed or removed its
    /// exchange): answers every write still queued, which no datagram will ever carry, with
    /// `error` (none: unanswered, a pair's leader that steps down after a unit may have taken
    /// over, which answers them) and forgets it; returns how many. Writes already carried by
    /// a sent datagram are not touched: they wait for their save, so flush the persister
    /// before destroying the producer, and they get `{"ok":true}`. A queued write saved ahead
    /// of its production is taken out of the file again (the image is saved as produced).
    std::size_t cancel_queued_writes(std::optional<std::string_view> error);
    /// A pair's leader stepping down: every write still queued, never to be produced here, taken
    /// out unanswered, as requests (target: the set topic, or the response topic) for the unit
    /// to leave to whichever leads next (PairWrites), which settles them. Saved ahead of its
    /// production, such a write is taken out of the file again, as by cancel_queued_writes.
    std::vector<WriteRequest> take_queued_writes();
    /// The image and its file, for the producer replacing this one (same layout).
    ImageHandover hand_over() const {
        return {{image_.data().begin(), image_.data().end()}, saves_.file};
    }

    /// Queues a validated write; its result is reported after the datagram carrying it is
    /// sent. Fails with rate_limited when a tag is written more often than its
    /// `max_writes_per_s`, and with queue_full when the queue is full.
    std::optional<core::write::WriteRejection> stage(std::vector<core::write::TagWrite> writes,
                                                     WriteReply reply, core::MonoTime now);

    /// The status at most once a second while its counters move (docs/mqtt-api.md); while
    /// saves fail, a save of the image once a second.
    void on_tick(core::MonoTime now);

    /// Reports every tag's value and the status again (after a reconnect).
    void republish(core::WallTime wall);

    // --- This unit's role (app/redundancy/unit_role.hpp, docs/redundancy.md) --------------
    /// Told of each image that writes changed once a datagram carrying it left
    /// (UnitRole::image_changed), and asked to answer each accepted write (`ok`, or `ok`
    /// unsaved: UnitRole::answer_write). Without a call: a single unit's (always_leads()).
    /// `role` must outlive the producer.
    void set_role(redundancy::UnitRole& role) { role_ = &role; }
    /// The standby takes the leader's image (the plan's length) as its own and saves it as any
    /// image; returns whether a byte changed. Writes still queued stay queued over it.
    bool follow_image(std::span<const std::byte> data);
    /// The standby heard the leader's datagram of this exchange with request id `heard`: its
    /// own next datagram continues after it.
    void continue_after(std::uint16_t heard) { image_.continue_after(heard); }

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
    const core::exchange::ProduceCounters& counters() const { return counters_; }
    /// True while sends fail (the status says paused).
    bool paused() const { return failing_; }
    /// True when the file holds the image being produced, or a newer one.
    bool saved() const { return save_.saved(); }
    const core::exchange::ProducedImage& image() const { return image_; }
    /// What its `_status` says, now.
    ProducedStatus status() const;
    /// When the last datagram left; nullopt before the first.
    std::optional<core::WallTime> last_sent() const { return last_sent_; }
    /// When this exchange's configuration took effect (the producer was made).
    core::WallTime configured_at() const { return configured_at_; }

private:
    /// Where the image is saved: the persister, this producer's key there, the file, and the
    /// log of failed saves.
    struct ImageSaves {
        adapters::state::ImagePersister& persister;
        adapters::state::ImagePersister::Key key;
        std::shared_ptr<adapters::state::ImageFile> file;  ///< shared with the saves under way
        core::ThrottledLog log;
    };
    /// The writes accepted: rate limits, and where each result goes, by write id.
    struct WriteIntake {
        std::vector<core::write::RateLimiter> limiters;  ///< one per tag
        std::unordered_map<std::uint64_t, WriteReply> replies;
        std::uint64_t next_id = 1;
    };
    /// The datagram being produced and the writes it is the first to carry.
    struct Outgoing {
        std::vector<std::byte> datagram;
        std::vector<std::uint64_t> carried;
    };
    /// `_status` pacing: at most once a second, at this producer's phase, while it sends.
    struct StatusPacing {
        core::exchange::StatusGrid grid;  ///< phase set by start()
        std::uint64_t last_sent = 0;      ///< counters_.sent when the status was last reported
    };

    /// Saves the image with every queued write applied, now or once the save under way is done.
    void request_save();
    /// A save is done: the writes it answers get their results, or it failed (below).
    void on_saved(const std::optional<std::string>& error);
    /// Sent writes answered `saved: false`, queued ones it held refused, and the producer saves
    /// ahead of production until a save succeeds.
    void on_save_failed(const core::exchange::SaveThenAnswer::Saved& saved);
    /// A queued write saved ahead of its production was taken out: the file gets the image as
    /// produced again.
    void unsave_queued(std::uint64_t first_taken);
    void report_echo(core::WallTime wall, bool all);
    void report_status();
    void report_results(std::span<const std::uint64_t> write_ids);
    /// Where the write's result goes, no longer waited for; none for a write already answered.
    std::optional<WriteReply> take_reply(std::uint64_t write_id);
    /// Answers an accepted write: `ok`, or `ok` with `unsaved`'s reason; through the gate.
    void answer_accepted(std::uint64_t write_id, WriteReply reply,
                         std::optional<std::string> unsaved);

    /// On the heap, at one address for the producer's life: image_ and the northbounds keep it.
    std::shared_ptr<const core::plan::ExchangePlan> plan_;
    adapters::udp::Endpoint destination_;
    ProducerScheduler& scheduler_;
    std::optional<ProducerScheduler::Id> id_;  ///< set by start(), reset by stop()
    Northbound& northbound_;
    ImageSaves saves_;
    ImageSaveTotals& totals_;
    core::exchange::ProducedImage image_;
    core::exchange::SaveThenAnswer save_;  ///< when the image is saved and writes answered
    WriteIntake writes_;
    Outgoing outgoing_;
    std::vector<std::byte> echoed_;  ///< data bytes as last reported
    StatusPacing status_;
    core::exchange::ProduceCounters counters_;
    bool failing_ = false;  ///< the last send failed: the status says paused
    std::optional<core::WallTime> last_sent_;
    core::WallTime configured_at_;
    redundancy::UnitRole* role_ = &redundancy::always_leads();
};

}  // namespace eip2mqtt::app
