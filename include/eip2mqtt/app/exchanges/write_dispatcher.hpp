#pragma once
/// Where every northbound's writes go (the Gateway's WriteHandler): a decoded write is staged on
/// its produced exchange, or refused; every refusal is counted, answered through `results` as
/// every other result is (the fan-out: it notes the result in the write log, then answers the
/// northbound the write came from), and logged (throttled: a client may flood). Time is
/// injected.
///
/// Threading: the loop only.

#include <cstddef>
#include <functional>
#include <optional>
#include <utility>

#include "eip2mqtt/app/exchanges/write_log.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/throttled_log.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

/// Stages `write` on its produced exchange; the exchange's refusal (rate limit, full queue) if
/// it refuses it.
using StageWrite = std::function<std::optional<core::write::WriteRejection>(
    ExchangeWrite&& write, const WriteReply& reply, core::MonoTime now)>;

class WriteDispatcher final : public WriteHandler {
public:
    /// `results` (where refusals are answered) and `clock` (when a write arrives, for its rate
    /// limit) must outlive the dispatcher.
    WriteDispatcher(StageWrite stage, Northbound& results, const core::Clock& clock);

    void on_write(WriteRequest&& request) override;

    /// This unit's role (docs/redundancy.md), asked what becomes of each write that reaches
    /// it (WriteRole::admit_write): applied, taken by the role unanswered, or refused with the
    /// role's refusal. Without a call: a single unit's, which applies every write. `role` must
    /// outlive the dispatcher.
    void set_role(redundancy::WriteRole& role) { role_ = &role; }
    /// A write that the unit this one took over from took, and never answered: it died, hung
    /// or was cut off from the broker first, or never had it. Refused as its northbound
    /// refused it; else, as the role says (WriteRole::settle_write), taken as any write (so it
    /// is answered `ok` once produced) or refused with the role's refusal. True when taken
    /// (answered once produced), false when refused.
    bool settle(WriteRequest&& request);
    /// Writes a reload answered `reloaded` (ExchangeProducer::cancel_queued_writes).
    void count_cancelled(std::size_t writes) { counters_.writes_cancelled += writes; }
    /// Where the produced exchanges count their image saves (ExchangeProducer).
    ImageSaveTotals& image_saves() { return counters_.image_saves; }
    const WriteCounters& counters() const { return counters_; }
    /// The last writes and their results (the status page): noted here as each arrives, and by
    /// the fan-out as each result passes it.
    WriteLog& write_log() { return write_log_; }
    const WriteLog& write_log() const { return write_log_; }

private:
    /// False when the write stops here (taken by the role, moved from `request`; or refused).
    bool admitted(WriteRequest& request);
    void reject(const WriteRequest& request, const core::write::WriteRejection& rejection);

    StageWrite stage_;
    Northbound& results_;
    const core::Clock& clock_;
    redundancy::WriteRole* role_ = &redundancy::always_leads();
    WriteCounters counters_;
    core::ThrottledLog log_;
    WriteLog write_log_;
};

}  // namespace eip2mqtt::app
