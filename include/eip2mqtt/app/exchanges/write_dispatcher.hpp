#pragma once
/// Where every northbound's writes go (the Gateway's WriteHandler): a decoded write is staged on
/// its produced exchange, or refused; every refusal is counted, answered through the northbound
/// the write came from, and logged (throttled: a client may flood). Time is injected.
///
/// Threading: the loop only.

#include <cstddef>
#include <functional>
#include <optional>
#include <utility>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/clock.hpp"
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
    WriteDispatcher(StageWrite stage, const core::Clock& clock);

    void on_write(WriteRequest&& request) override;

    /// What this unit's role (docs/redundancy.md) asks of the writes that reach it.
    struct WriteAdmission {
        /// Whether this unit takes a write now (unset: every write is).
        std::function<core::redundancy::WritePolicy()> policy;
        /// Takes each write left to the leader (redundancy::PairWrites); unset: dropped.
        std::function<void(WriteRequest&& request)> leave;
        /// Whether the produced image already holds what `write` writes (settle()).
        std::function<bool(const ExchangeWrite& write)> holds;
    };
    /// A write the leader answers is left to it here unanswered (counted); one that no live
    /// leader will answer is refused `standby`. Writes on the command port go to this unit's
    /// own address, which no leader answers: they are refused whenever this unit does not lead.
    void set_admission(WriteAdmission admission) { admission_ = std::move(admission); }
    /// A write that the leader this unit took over from was left, and never answered: it died,
    /// hung or was cut off from the broker first, or never had it. Refused as its northbound
    /// refused it; taken as this leader takes any write when the image already holds what it
    /// writes (the old leader applied it, and the image it published brought it here), so it
    /// is answered `ok` once produced; else refused `standby`: not applied here, and undone
    /// should the old leader have sent it. True when taken (answered once produced), false
    /// when refused.
    bool settle(WriteRequest&& request);
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
    const core::Clock& clock_;
    WriteAdmission admission_;
    WriteCounters counters_;
    core::ThrottledLog log_;
};

}  // namespace eip2mqtt::app
