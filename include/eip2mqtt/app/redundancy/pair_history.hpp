#pragma once
/// A pair's samples across a takeover (docs/redundancy.md), so that a subscriber of `_values`
/// and `_history` gets every sample:
/// - Both units keep each consumed exchange's last samples in a window
///   (core/redundancy/sample_window.hpp), as the exchange reports them, leading or not: the
///   FanOut hands them here ahead of its gate (FanOut::set_tap).
/// - The leader's JSON tree asks a token for the publication of each sample (token_for) and
///   the broker's acknowledgements come back here (on_acknowledged): the leader's watermarks
///   (core/redundancy/acked_watermarks.hpp), which its renewals carry (watermarks()).
/// - The standby keeps the watermarks of the last renewal it heard (heard()). Taking over
///   (took_over), it publishes on `{exchange}/_history`, through the JSON tree's HistorySink,
///   every windowed sample newer than its exchange's watermark, oldest first: at once as far as
///   the connection's backlog allows, the rest on the next ticks. Its own watermarks start at
///   those it heard.
/// - The same samples, in the same order, go to the session's sink too when there is one (the
///   Sparkplug edge node: historical DDATA), from when it may take them (born) on, at its own
///   pace (add_session_sink). The watermarks stay the JSON tree's: the one record of what the
///   old leader had delivered.
///
/// Threading: the loop only.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/leader_record.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/redundancy/acked_watermarks.hpp"
#include "eip2mqtt/core/redundancy/sample_window.hpp"

namespace eip2mqtt::app::redundancy {

struct PairHistoryCounters {
    std::uint64_t replayed = 0;  ///< samples published on `_history` after taking over
    /// Samples a window's count or byte bound pushed out before they were 2 x takeover old.
    std::uint64_t window_overflow = 0;
};

struct PairHistoryOptions {
    std::chrono::milliseconds takeover{2000};
    /// Every window together; each consumed exchange has an equal share.
    std::size_t max_bytes = std::size_t{32} << 20;
    /// The replay waits while the connection holds this many publications (live data first).
    std::uint64_t max_backlog = 1000;
};

class PairHistory final : public Northbound {
public:
    /// `sink` (the JSON tree) and `clock` must outlive this; `backlog` gives the publications
    /// waiting or in flight on the sink's connection.
    PairHistory(PairHistoryOptions options, history::HistorySink& sink,
                std::function<std::uint64_t()> backlog, const core::Clock& clock);

    /// Every consumed exchange's window: a kept exchange keeps its own.
    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    /// Keeps each sample a batch names (SampleBatch::key) in its exchange's window.
    void tag_samples(const SampleBatch& batch) override;

    /// The token the publication of `batch`'s sample carries (JsonTree::set_sample_tokens).
    std::uint64_t token_for(const SampleBatch& batch);
    /// An acknowledged token of the JSON tree's connection; false when it is not one of this.
    bool on_acknowledged(std::uint64_t token);
    /// What this unit's renewals carry.
    Watermarks watermarks() const;
    /// The watermarks of the last renewal heard from the leader.
    void heard(Watermarks&& watermarks) { heard_ = std::move(watermarks); }

    /// The replay goes only while `gate` says so (the gateway: a renewal sent since this unit
    /// leads was acknowledged, so it led, reaching the broker, after it took over): a unit cut
    /// off as it takes the lead hands nothing to a connection that carries nothing.
    void set_replay_gate(std::function<bool()> gate) { gate_ = std::move(gate); }
    /// Replays to `sink` as well, with no acknowledgement token, while `ready` says it may take
    /// history and its connection holds fewer than max_backlog publications (`backlog`).
    void add_session_sink(history::HistorySink& sink, std::function<bool()> ready,
                          std::function<std::uint64_t()> backlog);
    /// This unit leads from `now` on: the replay of what the leader had not had acknowledged.
    void took_over(core::MonoTime now);
    /// This unit stands by: nothing more is replayed, no watermark is its own; those it had
    /// count as heard until it hears the leader's.
    void stood_by();
    /// Every tick: the replay goes on.
    void on_tick() { replay_some(); }
    bool replaying() const { return !due_.empty(); }
    /// Samples the session's sink published after taking over.
    std::uint64_t session_replayed() const { return session_replayed_; }

    const PairHistoryCounters& counters() const { return counters_; }

private:
    struct Exchange {
        const core::plan::ExchangePlan* plan = nullptr;
        std::uint32_t id = 0;  ///< for the watermarks: never another exchange's
        core::redundancy::SampleWindow window;
    };
    struct Due {
        const Exchange* exchange = nullptr;
        core::redundancy::WindowedSample sample;
    };

    Exchange* find(const core::plan::ExchangePlan& plan);
    /// The windowed samples of `exchange` newer than its heard watermark, onto due_; how many.
    std::size_t take_due(Exchange& exchange, core::MonoTime now, bool& found);
    void replay_some();
    /// The session sink's part of replay_some().
    void replay_to_session();
    /// Empties due_ once every sink has replayed it.
    void drop_replayed();

    PairHistoryOptions options_;
    history::HistorySink& sink_;
    std::function<std::uint64_t()> backlog_;
    std::function<bool()> gate_;
    const core::Clock& clock_;
    using Exchanges =
        std::unordered_map<const core::plan::ExchangePlan*, std::unique_ptr<Exchange>>;
    Exchanges exchanges_;  ///< the running consumed exchanges, by plan
    std::uint32_t next_id_ = 0;
    core::redundancy::AckedWatermarks acked_;
    Watermarks heard_;
    std::vector<Due> due_;  ///< oldest first, from next_due_ on
    std::size_t next_due_ = 0;
    PairHistoryCounters counters_;
    struct SessionSink {
        history::HistorySink* sink = nullptr;
        std::function<bool()> ready;
        std::function<std::uint64_t()> backlog;
        std::size_t next_due = 0;  ///< its own place in due_
    };
    std::optional<SessionSink> session_;
    std::uint64_t session_replayed_ = 0;
};

}  // namespace eip2mqtt::app::redundancy
