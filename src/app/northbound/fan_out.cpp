#include "eip2mqtt/app/northbound/fan_out.hpp"

#include <algorithm>

namespace eip2mqtt::app::northbound {

void FanOut::excluding(std::span<Northbound* const> skipped, const std::function<void()>& run) {
    const auto before = skipped_;
    skipped_ = skipped;
    run();
    skipped_ = before;
}

bool FanOut::skipped(const Northbound* northbound) const {
    return !skipped_.empty() &&
           std::find(skipped_.begin(), skipped_.end(), northbound) != skipped_.end();
}

void FanOut::exchanges_changed(const ExchangeSet& running,
                               std::span<const std::string> retired_topics) {
    if (tap_) tap_->exchanges_changed(running, retired_topics);
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->exchanges_changed(running, retired_topics);
}

void FanOut::tag_samples(const SampleBatch& batch) {
    if (tap_) tap_->tag_samples(batch);
    if (closed()) return;
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->tag_samples(batch);
}

void FanOut::consumed_status(const ConsumedStatus& status) {
    if (closed()) return;
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->consumed_status(status);
}

void FanOut::produced_status(const core::plan::ExchangePlan& exchange,
                             const ProducedStatus& status) {
    if (closed()) return;
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->produced_status(exchange, status);
}

void FanOut::exchange_state(const core::plan::ExchangePlan& exchange,
                            core::exchange::ConsumeState state) {
    if (closed()) return;
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->exchange_state(exchange, state);
}

void FanOut::write_result(const WriteReply& reply, std::optional<std::string_view> error) {
    if (write_log_ != nullptr)
        write_log_->answered(reply.log_id, error.value_or("ok"), clock_->wall());
    // Answered in the protocol it was asked in: a DCMD's result is not a JSON topic's business.
    if (reply.origin != nullptr && reply.origin != this) reply.origin->write_result(reply, error);
}

void FanOut::write_result_unsaved(const WriteReply& reply, std::string_view reason) {
    if (write_log_ != nullptr) {
        write_log_->answered(reply.log_id, "ok, not saved: " + std::string(reason), clock_->wall());
    }
    if (reply.origin != nullptr && reply.origin != this) {
        reply.origin->write_result_unsaved(reply, reason);
    }
}

void FanOut::gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) {
    for (auto* northbound : northbounds_)
        if (!skipped(northbound)) northbound->gateway_metrics(sources, uptime);
}

}  // namespace eip2mqtt::app::northbound
