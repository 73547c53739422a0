#pragma once
/// Several northbounds at once (the JSON tree beside Sparkplug B, say): every event goes to each,
/// in the order they were added, but a write result goes only to the northbound the write came
/// from.
///
/// Threading: the loop only.

#include <functional>
#include <span>
#include <vector>

#include "eip2mqtt/app/exchanges/write_log.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app::northbound {

class FanOut final : public Northbound {
public:
    /// `northbound` must outlive the fan-out's use of it.
    void add(Northbound& northbound) { northbounds_.push_back(&northbound); }
    /// A unit that does not lead (docs/redundancy.md) says nothing of the exchanges: while
    /// `role` (which must outlive the fan-out) says it does not, samples, statuses and
    /// exchange states stop here. The running set, write results and the gateway's own
    /// metrics still pass. Unset: the unit always leads, everything passes.
    void set_role(const redundancy::UnitRole& role) { role_ = &role; }
    /// What sees the running set and every sample, gate open or closed, ahead of the
    /// northbounds: the window of samples of a redundant unit (app/redundancy/pair_history),
    /// kept while it does not lead so that it can publish what was missed once it does.
    void set_tap(Northbound& tap) { tap_ = &tap; }
    /// Where each write result passing here is noted, stamped by `clock` (both must outlive
    /// the fan-out's use of them).
    void set_write_log(WriteLog& log, const core::Clock& clock) {
        write_log_ = &log;
        clock_ = &clock;
    }

    /// Runs `run` with the events it makes kept from `skipped` (which outlives the call): one
    /// MQTT connection that connects again says the retained state again, and the topic
    /// trees of the other connections, which said it already, do not repeat it.
    void excluding(std::span<Northbound* const> skipped, const std::function<void()>& run);

    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    void tag_samples(const SampleBatch& batch) override;
    void consumed_status(const ConsumedStatus& status) override;
    void produced_status(const core::plan::ExchangePlan& exchange,
                         const ProducedStatus& status) override;
    void exchange_state(const core::plan::ExchangePlan& exchange,
                        core::exchange::ConsumeState state) override;
    void write_result(const WriteReply& reply, std::optional<std::string_view> error) override;
    void write_result_unsaved(const WriteReply& reply, std::string_view reason) override;
    void gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) override;

private:
    bool closed() const { return !role_->leads(); }
    bool skipped(const Northbound* northbound) const;

    std::vector<Northbound*> northbounds_;
    const redundancy::UnitRole* role_ = &redundancy::always_leads();
    WriteLog* write_log_ = nullptr;
    const core::Clock* clock_ = nullptr;
    Northbound* tap_ = nullptr;
    std::span<Northbound* const> skipped_;
};

}  // namespace eip2mqtt::app::northbound
