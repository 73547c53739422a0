#pragma once
/// One consumed exchange at run time: its ConsumedExchange state, its producer's clock, and the
/// report-by-exception filter of each tag; what they lead to goes to the Northbound as events
/// (tag samples, status, state), in no protocol's terms.
///
/// Changes of its state and its producer's clock are reported at most once per period
/// (core::exchange::ChangePacer) and logged line by line only while they are few
/// (core::exchange::ChangeLog): a stream alternating good and bad datagrams republishes each
/// tag's quality and the `_status` once a period, not once a datagram, and is logged as a
/// summary.
///
/// Threading: the loop only.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/exchange/arrival_stats.hpp"
#include "eip2mqtt/core/exchange/change_log.hpp"
#include "eip2mqtt/core/exchange/change_pacer.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"
#include "eip2mqtt/core/exchange/status_grid.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/quality/report_filter.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

class ExchangeConsumer {
public:
    /// `northbound` must outlive the consumer; `clock` tells when it was configured.
    ExchangeConsumer(core::plan::ExchangePlan plan, Northbound& northbound,
                     const core::Clock& clock = adapters::clock::system_clock());

    /// A datagram whose key matched this exchange.
    core::exchange::ConsumeOutcome on_datagram(const core::wire::Datagram& datagram,
                                               core::MonoTime now, core::WallTime wall);

    /// Timeout, refresh and throttled status; `refresh_scan` also checks refresh_s (the
    /// caller asks for it about once a second: refresh is counted in seconds).
    void on_tick(core::MonoTime now, core::WallTime wall, bool refresh_scan);

    /// Reports every tag, the state and the status again (after a reconnect: brokers lose
    /// retained state; and when a pair's standby takes the lead, its northbounds having heard
    /// nothing while it stood by).
    void republish(core::MonoTime now);

    /// This consumer is `index` of `count` started together: its periodic `_status` goes at its
    /// own phase of the second (StatusGrid).
    void set_status_phase(std::size_t index, std::size_t count) {
        status_grid_.set_phase(index, count);
    }

    const core::plan::ExchangePlan& plan() const { return plan_; }
    const core::exchange::ConsumedExchange& exchange() const { return exchange_; }
    const core::exchange::RemoteProducerClock& clock() const { return clock_; }
    /// Inter-arrival period and jitter of accepted datagrams.
    const core::exchange::ArrivalStats& arrivals() const { return arrivals_; }
    /// A datagram of this exchange from an address other than its `source`.
    /// ConsumedExchange::accepts_source: false (and counted) for a datagram to drop.
    bool accepts_source(std::uint32_t address) { return exchange_.accepts_source(address); }
    std::uint64_t wrong_source() const { return exchange_.counters().wrong_source; }
    /// When this exchange's configuration took effect (the consumer was made).
    core::WallTime configured_at() const { return configured_at_; }
    /// What its `_status` says, now.
    ConsumedStatus status() const { return {plan_, exchange_, last_seen_ms_, clock_}; }
    /// The timestamp of the values its tags report (ms since 1970).
    std::int64_t timestamp_ms() const { return timestamp_ms_; }

private:
    /// `key` names the sample (SampleBatch::key); none for a refresh or a republish.
    void report_tags(core::MonoTime now, bool all,
                     std::optional<core::redundancy::SampleKey> key = std::nullopt);
    /// The tags again, at a change of quality (stale, mismatch) that no datagram brought.
    void report_quality_change(core::MonoTime now);
    /// After the state or the clock moved: reports the change now, or holds it for the
    /// ChangePacer (or forgets a held one when the exchange is back to what was reported).
    /// True when it reported.
    bool settle(core::MonoTime now);
    /// Reports what changed since the last report: the tags' quality and the state if the state
    /// changed, and the status.
    void report_change(core::MonoTime now);
    /// Whether what is reported is what the exchange is in (no change held).
    bool reported_current() const {
        return exchange_.state() == reported_state_ && clock_.state() == reported_clock_;
    }
    /// `periodic`: the once-a-second report (on the StatusGrid), not a state change's.
    void report_status(core::MonoTime now, bool periodic = false);
    /// The timestamp of the accepted datagram's tags (RemoteProducerClock), logging a clock change.
    std::int64_t sample_time(core::MonoTime now, core::WallTime wall);
    void log_clock(bool first, core::MonoTime now);
    /// Logs the exchange going stale, into a mismatch (with `datagram`'s detail) and coming
    /// back, each once, through change_log_.
    void log_state_change(core::exchange::ConsumeState before, core::MonoTime now,
                          const core::wire::Datagram* datagram = nullptr);
    /// Whether a change at `now` has its own line (else it is counted, and a summary written
    /// when due).
    bool log_change(core::MonoTime now);
    void log_summary(std::uint64_t changes);

    core::plan::ExchangePlan plan_;
    Northbound& northbound_;
    core::exchange::ConsumedExchange exchange_;
    std::vector<core::quality::ReportFilter> filters_;  ///< one per tag of plan_.tags
    core::exchange::ArrivalStats arrivals_;
    core::exchange::RemoteProducerClock clock_;
    bool clock_seen_ = false;                   ///< a datagram was accepted since start
    std::int64_t timestamp_ms_ = 0;             ///< of the values the tags report
    core::redundancy::SampleKey key_;           ///< of the last sample reported
    std::optional<std::int64_t> last_seen_ms_;  ///< wall time of the last accepted datagram
    core::exchange::StatusGrid status_grid_;
    std::uint64_t last_status_received_ = 0;
    bool status_dirty_ = true;
    core::MonoTime down_since_{};  ///< when the exchange last left `ok`
    /// What the tags, the state and the status last reported.
    core::exchange::ConsumeState reported_state_ = core::exchange::ConsumeState::waiting;
    core::exchange::ClockState reported_clock_ = core::exchange::ClockState::none;
    core::exchange::ChangePacer pacer_;
    core::exchange::ChangeLog change_log_;
    core::WallTime configured_at_;
};

}  // namespace eip2mqtt::app
