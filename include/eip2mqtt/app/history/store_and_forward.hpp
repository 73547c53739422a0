#pragma once
/// Store and forward: while the MQTT connection is down, every accepted datagram's
/// changes (and every quality change) go to the journal on disk, in arrival order; once the
/// broker is back and the current state republished, they are replayed oldest first, at most
/// `replay_rate` a second and only while live publications are not waiting, to a HistorySink
/// (the JSON tree's `_history`), and to each other sink added (the Sparkplug node) once its own
/// connection is up: each has its own SinkReplay. An entry leaves the journal only when the
/// broker acknowledged its replay to every sink that has a use for it.
///
/// The cut between live and journaled is journaling(), whether the first sink's link is up: the
/// JSON tree asks its connection the same question before it publishes `_values`, at the same
/// moment on the same loop, so every sample goes either live or to the journal, never both and
/// never neither.
///
/// Threading: the loop only. The journal's appends and commits run on the JournalWriter's
/// thread, handed over once a tick; reads and deletions on the loop, under its lock.

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/history/journal.hpp"
#include "eip2mqtt/adapters/history/journal_writer.hpp"
#include "eip2mqtt/adapters/history/sample_codec.hpp"
#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/app/history/sink_replay.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::history {

struct StoreAndForwardOptions {
    std::uint32_t replay_rate = 2000;
    std::chrono::milliseconds fsync_interval{1000};
    /// The loop time one tick's replay may take (one entry at least): the rate counts entries,
    /// and an entry of a wide exchange costs the loop as much as its many tags, so without it
    /// a replay could keep the loop from its datagrams until the socket's buffer overflowed.
    std::chrono::microseconds replay_budget{2000};
    /// Where that time is read (tests give their own); it must outlive the StoreAndForward.
    const core::Clock* clock = &adapters::clock::system_clock();
};

struct HistoryStats {
    adapters::history::JournalStats journal;
    std::uint64_t journaled = 0;  ///< entries appended since start
    std::uint64_t replayed = 0;   ///< entries the broker acknowledged since start
    /// Entries whose exchange is gone or changed its tags since: they cannot be replayed.
    std::uint64_t discarded = 0;
    std::uint64_t failures = 0;  ///< journal operations that failed (logged)
    bool replaying = false;
    std::int64_t taken_at_ms = 0;  ///< wall time of these figures, for the oldest entry's age
};

class StoreAndForward final : public Northbound {
public:
    StoreAndForward(std::unique_ptr<adapters::history::Journal> journal,
                    StoreAndForwardOptions options, LinkProbe link, HistorySink& sink);
    ~StoreAndForward() override;

    /// Another sink the replay goes to as well, on a connection of its own (the Sparkplug
    /// node's): its replay starts with on_connected(sink), and rewinds then, since what it was
    /// handed before went with its last connection (a session-bound client drops it).
    void add_sink(HistorySink& sink, LinkProbe link) {
        extra_.push_back(std::make_unique<SinkReplay>(sink, std::move(link)));
    }

    /// Blocks until everything journaled so far is committed (tests).
    void flush() { writer_.flush(); }

    /// True while samples go to the journal instead of the live `_values`.
    bool journaling() const { return !first_.link().connected(); }

    /// After the reconnect's republish: the replay of what the journal holds begins.
    void on_connected(core::MonoTime now);
    /// An added sink may publish history again (its connection is up, its births made).
    void on_connected(HistorySink& sink, core::MonoTime now);
    /// The broker acknowledged the replay of entry `id` to the first sink.
    void on_acknowledged(std::uint64_t id);
    /// The broker acknowledged the replay of entry `id` to an added sink.
    void on_acknowledged(HistorySink& sink, std::uint64_t id);
    /// Every gateway tick: commits what was journaled (durably every fsync interval), deletes
    /// acknowledged entries, replays what the rate allows.
    void on_tick(core::MonoTime now);
    HistoryStats stats();
    const StoreAndForwardOptions& options() const { return options_; }

    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    void tag_samples(const SampleBatch& batch) override;

private:
    struct Known {
        const core::plan::ExchangePlan* plan = nullptr;
        std::uint64_t layout = 0;
    };

    void replay_some(SinkReplay& replay, core::MonoTime now, bool first);
    /// Hands one entry to `replay`'s sink; false when it cannot be replayed (then it is deleted).
    bool replay_entry(SinkReplay& replay, const adapters::history::JournalEntry& entry);
    /// Why `entry` cannot be replayed (empty: it can, and samples_ holds its samples).
    std::string unusable(const adapters::history::JournalEntry& entry);
    /// Deletes what every sink has.
    void delete_delivered();
    SinkReplay* replay_of(HistorySink& sink);
    void fail(const char* what, const std::exception& error);

    adapters::history::JournalWriter writer_;
    StoreAndForwardOptions options_;
    SinkReplay first_;  ///< the JSON tree's, whose connection decides what is journaled
    std::vector<std::unique_ptr<SinkReplay>> extra_;
    std::map<std::string, Known, std::less<>> exchanges_;
    /// The same by plan, for the data path (a kept exchange keeps its plan object).
    std::unordered_map<const core::plan::ExchangePlan*, std::uint64_t> layouts_;

    std::vector<adapters::history::JournalEntry> pending_;  ///< for the writer, at the next tick
    std::vector<adapters::history::JournaledSample> journaled_samples_;
    std::vector<TagSample> samples_;  ///< of a replayed entry
    core::MonoTime last_durable_{};

    std::uint64_t deleted_through_ = 0;  ///< every entry up to it is deleted
    std::uint64_t replay_started_with_ = 0;
    core::MonoTime replay_started_{};

    std::uint64_t journaled_ = 0;
    std::uint64_t replayed_ = 0;
    std::uint64_t discarded_ = 0;
    std::uint64_t failures_ = 0;
    core::ThrottledLog failure_log_;
    core::ThrottledLog discard_log_;
};

/// A fingerprint of an exchange's tags (names, types, addresses): a journaled entry is replayed
/// only into an exchange with the layout it was journaled with.
std::uint64_t layout_fingerprint(const core::plan::ExchangePlan& plan);

}  // namespace eip2mqtt::app::history
