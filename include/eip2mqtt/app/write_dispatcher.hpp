#pragma once
/// Where every northbound's writes go (the Gateway's WriteHandler): a decoded write is staged on
/// its produced exchange, or refused; every refusal is counted, answered through the northbound
/// the write came from, and logged (throttled: a client may flood). Time is injected.
///
/// Threading: the loop only.

#include <cstddef>
#include <deque>
#include <functional>
#include <optional>
#include <utility>

#include "eip2mqtt/app/clock.hpp"
#include "eip2mqtt/app/gateway_metrics.hpp"
#include "eip2mqtt/app/northbound.hpp"
#include "eip2mqtt/core/redundancy/lease.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

/// Stages `write` on its produced exchange; the exchange's refusal (rate limit, full queue) if
/// it refuses it.
using StageWrite = std::function<std::optional<core::write::WriteRejection>(
    ExchangeWrite&& write, const WriteReply& reply, core::MonoTime now)>;

class WriteDispatcher final : public WriteHandler {
public:
    /// `clock` (when a write arrives, for its rate limit) must outlive the dispatcher.
    WriteDispatcher(StageWrite stage, const Clock& clock);

    void on_write(WriteRequest&& request) override;
    /// The standby of a pair (README "Redundancy"): whether this unit takes a write now. A
    /// write the leader answers is dropped here unanswered (counted); one that no live leader
    /// will answer is refused `standby`. Writes on the command port go to this unit's own
    /// address, which no leader answers: they are refused whenever this unit does not lead.
    /// Unset: every write is taken.
    void set_admission(std::function<core::redundancy::WritePolicy()> admission) {
        admission_ = std::move(admission);
    }
    /// This unit took the lead from a leader last heard at `last_heard`. The writes it left to
    /// that leader since then may never have reached it (it died, or was cut off from the
    /// broker, before them; its renewals vouch for nothing after the last one heard): they are
    /// refused `standby` now, so each is answered, and never applied here, where the old leader
    /// may have applied it. Those left before it are the old leader's.
    void took_over(core::MonoTime last_heard);
    /// Writes a reload answered `reloaded` (ExchangeProducer::cancel_queued_writes).
    void count_cancelled(std::size_t writes) { counters_.writes_cancelled += writes; }
    /// Where the produced exchanges count their image saves (ExchangeProducer).
    ImageSaveTotals& image_saves() { return counters_.image_saves; }
    const WriteCounters& counters() const { return counters_; }

private:
    /// False when the write stops here (left to the leader, then kept, moved from `request`;
    /// or refused `standby`).
    bool admitted(WriteRequest& request);
    void reject(const WriteRequest& request, const core::write::WriteRejection& rejection);

    StageWrite stage_;
    const Clock& clock_;
    std::function<core::redundancy::WritePolicy()> admission_;
    struct LeftToLeader {
        WriteRequest request;
        core::MonoTime at;
    };
    /// The newest writes left to the leader (bounded: only those of the last takeover window
    /// can matter, and a live leader answers all of them).
    std::deque<LeftToLeader> left_to_leader_;
    WriteCounters counters_;
    core::ThrottledLog log_;
};

}  // namespace eip2mqtt::app
