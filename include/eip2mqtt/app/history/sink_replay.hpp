#pragma once
/// One northbound's way through the store-and-forward journal: each has its own, since each
/// has its own MQTT connection, back at its own moment after an outage. Where it is (the last
/// entry handed over), what it was handed and has not had acknowledged, how many entries its
/// rate allows now, and how far every entry is delivered to it (through()): the journal keeps
/// an entry until every northbound has it.
///
/// Threading: the loop only.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>

#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::history {

/// What store and forward needs of a northbound's MQTT connection, asked on the loop.
struct LinkProbe {
    /// True while the northbound may publish history (connected; a Sparkplug node born).
    std::function<bool()> connected;
    /// Publications waiting or in flight: replay waits while live data queues, and an empty
    /// client with replayed entries still unacknowledged means the client dropped them.
    std::function<std::uint64_t()> backlog;
};

class SinkReplay {
public:
    SinkReplay(HistorySink& sink, LinkProbe link) : sink_(&sink), link_(std::move(link)) {}

    HistorySink& sink() const { return *sink_; }
    const LinkProbe& link() const { return link_; }

    /// Its connection is up (again): the replay starts. `rewind`: what it was handed and never
    /// had acknowledged went with the last connection, and goes again.
    void start(core::MonoTime now, bool rewind);
    /// Nothing more to replay.
    void finish() { active_ = false; }
    bool active() const { return active_; }

    /// How many entries may be handed over now: what the rate allows, within the window of
    /// unacknowledged ones, while live publications do not queue. 0 while disconnected. When
    /// the client holds none of the unacknowledged ones, it dropped them: they go again.
    std::size_t room(core::MonoTime now, double rate);
    /// The entry after which the next read starts.
    std::uint64_t cursor() const { return cursor_; }
    /// Entry `id` was handed over; `outstanding`: it waits for an acknowledgement (otherwise
    /// the sink had no use for it, and it counts as delivered).
    void handed(std::uint64_t id, bool outstanding);
    /// Every tick between its replays: entries journaled (for another sink) while this one
    /// was connected, and stayed connected for a grace period after, count as delivered: it
    /// published them live. (The grace covers a connection that went before it was noticed.)
    /// `last_id`: the last entry journaled so far.
    void note_live(core::MonoTime now, std::uint64_t last_id);
    /// The broker acknowledged `id`; false when it was not waited for (a rewind forgot it).
    bool acknowledge(std::uint64_t id);
    /// Every entry up to this one is delivered to this sink.
    std::uint64_t through() const {
        return outstanding_.empty() ? cursor_ : *outstanding_.begin() - 1;
    }
    std::size_t outstanding() const { return outstanding_.size(); }
    /// How many entries to read for the next tick: twice what the last tick's time allowed
    /// when it ran out of time (no more is read than can be handed), otherwise any number.
    std::size_t pace() const { return pace_; }
    /// The last tick handed `handed` entries; `out_of_time`: its time ran out before the rest.
    void paced(std::size_t handed, bool out_of_time);

private:
    void rewind();

    HistorySink* sink_;
    LinkProbe link_;
    bool active_ = false;
    std::uint64_t cursor_ = 0;             ///< the last entry handed over
    std::set<std::uint64_t> outstanding_;  ///< handed over, not acknowledged yet
    double allowance_ = 0;                 ///< entries the rate allows now
    std::optional<core::MonoTime> last_;
    int idle_with_outstanding_ = 0;             ///< ticks the client held none of outstanding_
    std::optional<core::MonoTime> live_since_;  ///< connected between replays since then
    std::uint64_t live_mark_ = 0;               ///< the last entry journaled then
    std::size_t pace_ = SIZE_MAX;
};

}  // namespace eip2mqtt::app::history
