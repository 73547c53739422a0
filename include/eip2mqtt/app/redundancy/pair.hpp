#pragma once
/// A hot-standby pair (docs/redundancy.md), one object: the lease on a connection of its own,
/// and the role (UnitRole) that the parts it gates ask: what the exchanges say north (the
/// FanOut), what they produce (the ProducerScheduler, through Exchanges' options), the images
/// that writes changed and when a write is answered (each ExchangeProducer), and the writes
/// (the WriteDispatcher, as PairAdmission takes them). And what lets a takeover go on where the
/// leader stopped: its images, published by the leader and followed by the standby
/// (PairImages), its request ids, heard by the standby (UnitRole::follows_produced), its
/// samples: the new leader publishes on `_history` those the old one had not had acknowledged
/// (PairHistory), and the Sparkplug session of the one edge node, held by the leader alone
/// (SessionHooks).
///
/// Built in two steps, as its gates are: constructed before the parts it gates (may_send()
/// goes into their connections' options, exchanges_options() into the exchanges'), then
/// wire()d to them once they exist. Nothing runs before start().
///
/// Threading: the loop, but for the functions that may_send() returns (the sender threads).

#include <atomic>
#include <boost/asio/any_io_executor.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "eip2mqtt/app/redundancy/pair_admission.hpp"
#include "eip2mqtt/app/redundancy/pair_connection.hpp"
#include "eip2mqtt/app/redundancy/pair_history.hpp"
#include "eip2mqtt/app/redundancy/pair_images.hpp"
#include "eip2mqtt/app/redundancy/pair_writes.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/redundancy/lease.hpp"

namespace eip2mqtt::core::config {
struct Config;
}
namespace eip2mqtt::app {
class WriteDispatcher;
}
namespace eip2mqtt::app::northbound {
class FanOut;
}
namespace eip2mqtt::app::northbound::json_tree {
class JsonTree;
}

namespace eip2mqtt::app::redundancy {

class PairLease;

/// The session of the one Sparkplug edge node, which only the leader holds; every hook empty
/// without `sparkplug:`.
struct SessionHooks {
    /// Opens the session, with a bdSeq other than `heard_bd_seq` (the pair's last one).
    std::function<void(std::optional<std::uint8_t> heard_bd_seq)> open;
    /// Ends it: its NDEATH said, what waited dropped.
    std::function<void()> end;
    /// The bdSeq of the open session; nullopt while none is.
    std::function<std::optional<std::uint8_t>()> bd_seq;
    /// Where the session takes history (the edge node's historical DDATA): what the old leader
    /// had not had acknowledged reaches its hosts too after a takeover, once `history_ready`
    /// (the node is born), at the pace of its connection (`history_backlog`). Null: none.
    history::HistorySink* history = nullptr;
    std::function<bool()> history_ready;
    std::function<std::uint64_t()> history_backlog;
};

/// What the pair wires, borrowed: each must outlive the Pair's use of it (until stop()).
struct PairParts {
    const core::config::Config& config;
    /// The publications of the JSON tree's connection queued and in flight.
    std::function<std::uint64_t()> tree_backlog;
    northbound::json_tree::JsonTree& tree;
    WriteDispatcher& writes;
    Exchanges& exchanges;
    northbound::FanOut& north;  ///< every northbound
    SessionHooks session;
    /// Every running exchange's retained state again, and the JSON tree's `_meta` topics: a
    /// new leader says all of it at once.
    std::function<void()> republish;
};

class Pair final : public UnitRole {
public:
    /// `clock` must outlive the pair and be safe to read from any thread (the sender threads
    /// read it through may_send()). Its connection is an MQTT client on `loop`.
    Pair(boost::asio::any_io_executor loop, const core::Clock& clock);
    /// Its connection is the one `connect` makes in wire() (a test's fake broker).
    Pair(const core::Clock& clock, PairConnector connect);
    ~Pair();
    Pair(const Pair&) = delete;
    Pair& operator=(const Pair&) = delete;

    /// ClientOptions::may_send of the connections whose publications the pair fences, asked on
    /// their sender threads: what only a leader says (`leader_only`, every publication when
    /// null) goes only while this unit leads, by the lease as the loop last saw it. So what
    /// waited when the lease lapsed (a leader cut off from the broker, or resumed after
    /// SIGSTOP) is never said. The pair must outlive the connection.
    std::function<bool(const adapters::mqtt::Message&)> may_send(
        std::function<bool(const adapters::mqtt::Message&)> leader_only);
    /// The options of the exchanges that a pair sets: the role they ask (this pair) about
    /// production, the images the leader publishes, its answers and the request ids the standby
    /// follows. It is asked only once wire() made the lease: exchanges run from start() on.
    ExchangesOptions exchanges_options();
    /// Between a connection and its publisher: nothing passes unless this unit leads (the
    /// Sparkplug node's, whose session is the leader's).
    std::unique_ptr<adapters::mqtt::Publisher> leader_only(adapters::mqtt::Publisher& inner);

    /// The lease on its own connection, the images, the writes left to the leader, the
    /// history (with the JSON tree among the northbounds), and the gates they keep.
    void wire(PairParts parts);
    /// The connection started, its handlers set.
    void start();
    /// Before the other parts' ticks: the lease's claims, renewals and fence.
    void tick(core::MonoTime now);
    /// After store and forward's tick: the replay of a takeover goes on.
    void tick_replay();
    /// The lease goes, its will clearing the leader topic, once queued publications went or
    /// `flush_timeout` passed.
    void stop(std::chrono::milliseconds flush_timeout);

    /// Whether this unit leads at `now`.
    bool leading(core::MonoTime now) const;
    /// Whether it leads now, by its clock.
    bool leads() const override { return leading(clock_.monotonic()); }
    /// `{"pair":"turbine","role":"leader","epoch":4,"lease_left_ms":1250}`: the lease as this
    /// unit holds it now; `lease_left_ms` null while it does not lead.
    std::string status_json() const override;
    bool may_produce(core::MonoTime now) const override;
    /// The other unit sends what this one produces while this one stands by.
    bool hears_produced() const override { return true; }
    /// A standby follows the leader's request ids.
    bool follows_produced(core::MonoTime now) const override;
    /// The leader publishes the changed image for the standby (PairImages).
    void image_changed(const ExchangeProducer& producer) override;
    /// The leader answers once the broker has the image carrying the write
    /// (PairImages::answer_after_image).
    void answer_write(const ExchangeProducer& producer, std::uint64_t write_id,
                      const WriteReply& reply, std::function<void()> answer) override;
    /// The writes as PairAdmission takes them (wire() made it).
    WriteTurn admit_write(WriteRequest& request, core::write::WriteCounters& counters) override;
    WriteTurn settle_write(const WriteRequest& request,
                           core::write::WriteCounters& counters) override;
    core::write::WriteRejection refusal() const override;
    /// Whether on_acknowledged() wants the JSON tree connection's acknowledgements.
    bool hears_acknowledgements() const { return history_ != nullptr; }
    /// An acknowledged publication of the JSON tree's connection; false when it is not one of
    /// the pair's samples (a journal entry of store and forward).
    bool on_acknowledged(std::uint64_t token);

    const PairImageCounters& image_counters() const { return images_->counters(); }
    /// Null without history (no JSON tree among the northbounds).
    const PairHistoryCounters* history_counters() const {
        return history_ ? &history_->counters() : nullptr;
    }
    const PairWriteCounters& write_counters() const { return writes_->counters(); }

private:
    void make_writes();
    void make_history();
    /// The leader: every produced image, under its epoch.
    void publish_images();
    void on_message(const adapters::mqtt::Incoming& message);
    void on_pair_acknowledged(std::uint64_t token);
    void on_role(core::redundancy::Role role);
    /// Taking the lead: the writes left to the old leader and the answers this unit withheld.
    void settle_left_writes(core::MonoTime now);
    /// Answers again a left write the old leader's images list as answered, as they list it.
    void repeat_answer(const ListedWrite& write);
    /// Stepping down: the answers and the queued writes of this unit as leader.
    void step_down_writes(core::MonoTime now);
    /// After each event of the lease: leading_until_ from it.
    void refresh_leading_until();

    const core::Clock& clock_;
    PairConnector connect_;
    std::optional<PairParts> parts_;
    std::unique_ptr<PairConnection> client_;
    std::unique_ptr<PairLease> lease_;
    std::unique_ptr<PairImages> images_;
    /// What becomes of the writes that reach this unit.
    std::unique_ptr<PairAdmission> admission_;
    /// The writes left to the leader, until it answers them.
    std::unique_ptr<PairWrites> writes_;
    /// With the JSON tree: the samples a takeover replays on `_history`.
    std::unique_ptr<PairHistory> history_;
    /// The instant (steady clock, in its ticks) this unit's lease lapses while it leads; the
    /// least there is while it does not. Written on the loop, read by the sender threads.
    std::atomic<core::MonoTime::rep> leading_until_{
        core::MonoTime::min().time_since_epoch().count()};
};

}  // namespace eip2mqtt::app::redundancy
