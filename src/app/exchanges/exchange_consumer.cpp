#include "eip2mqtt/app/exchanges/exchange_consumer.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "eip2mqtt/core/plan/published_value.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::app {

ExchangeConsumer::ExchangeConsumer(core::plan::ExchangePlan plan, Northbound& northbound,
                                   const core::Clock& clock)
    : plan_(std::move(plan)),
      northbound_(northbound),
      exchange_(plan_),
      clock_(plan_.timestamp, plan_.clock_tolerance),
      pacer_(plan_.spec.period),
      configured_at_(clock.wall()) {
    filters_.resize(plan_.tags.size());
}

std::int64_t ExchangeConsumer::sample_time(core::MonoTime now, core::WallTime wall) {
    const auto& header = exchange_.last_header();
    const auto before = clock_.state();
    const auto timestamp = clock_.on_datagram(header.time_s, header.time_ns, core::to_ms(wall));
    if (clock_.state() != before || !clock_seen_) log_clock(!clock_seen_, now);
    clock_seen_ = true;
    return timestamp;
}

void ExchangeConsumer::log_clock(bool first, core::MonoTime now) {
    using core::exchange::ClockState;
    if (first && clock_.state() == ClockState::synced) return;  // the normal case: nothing to say
    if (!log_change(now)) return;
    const auto& name = plan_.spec.name;
    const bool producer_time = plan_.timestamp == core::plan::TimestampSource::producer;
    const bool receive_time = plan_.timestamp == core::plan::TimestampSource::receive;
    switch (clock_.state()) {
        case ClockState::unsynced:
            spdlog::warn(
                "exchange {}: the producer's clock is {} ms off the receive time (tolerance {} "
                "ms): its tags carry {}",
                name, clock_.offset_ms().value_or(0), clock_.tolerance().count(),
                producer_time ? "the producer's time all the same (timestamp: producer)"
                              : "the receive time");
            break;
        case ClockState::synced:
            spdlog::info(
                "exchange {}: the producer's clock is within {} ms of the receive time "
                "again: its tags carry {}",
                name, clock_.tolerance().count(),
                receive_time ? "the receive time (timestamp: receive)" : "the producer's time");
            break;
        case ClockState::none:
            spdlog::info(
                "exchange {}: datagrams carry no timestamp: its tags carry the receive "
                "time",
                name);
            break;
    }
}

bool ExchangeConsumer::log_change(core::MonoTime now) {
    const auto line = change_log_.on_change(now);
    if (line.summary > 0) log_summary(line.summary);
    return line.single;
}

void ExchangeConsumer::log_summary(std::uint64_t changes) {
    spdlog::warn(
        "exchange {}: {} change{} of state or clock in the last {} s, too many to log each; "
        "reported at most once a period ({} ms); now {}, clock {}",
        plan_.spec.name, changes, changes == 1 ? "" : "s", change_log_.interval().count(),
        plan_.spec.period.count(), core::exchange::to_string(exchange_.state()),
        core::exchange::to_string(clock_.state()));
}

void ExchangeConsumer::log_state_change(core::exchange::ConsumeState before, core::MonoTime now,
                                        const core::wire::Datagram* datagram) {
    using core::exchange::ConsumeState;
    const auto after = exchange_.state();
    const bool mismatch =
        after == ConsumeState::signature_mismatch || after == ConsumeState::length_mismatch;
    const bool back = after == ConsumeState::ok && before != ConsumeState::waiting;
    if ((after == ConsumeState::stale || back || (mismatch && datagram)) && log_change(now)) {
        if (after == ConsumeState::stale) {
            spdlog::warn("exchange {} is stale: no datagram for {} ms; tags marked stale",
                         plan_.spec.name, plan_.timeout.count());
        } else if (back) {
            spdlog::info("exchange {} is ok again after {:.1f} s {}; tags good", plan_.spec.name,
                         std::chrono::duration<double>(now - down_since_).count(),
                         core::exchange::to_string(before));
        } else {
            spdlog::warn("exchange {}: {} (received {} data bytes, configured {}, signature {})",
                         plan_.spec.name, core::exchange::to_string(after), datagram->data.size(),
                         plan_.length,
                         core::wire::to_string(
                             core::wire::Signature::from_wire(datagram->header.signature)));
        }
    }
    if (before == ConsumeState::ok || before == ConsumeState::waiting) down_since_ = now;
}

core::exchange::ConsumeOutcome ExchangeConsumer::on_datagram(const core::wire::Datagram& datagram,
                                                             core::MonoTime now,
                                                             core::WallTime wall) {
    const auto state_before = exchange_.state();
    const auto outcome = exchange_.on_datagram(datagram, now);
    const auto clock_before = clock_.state();
    if (outcome.state_changed) log_state_change(state_before, now, &datagram);
    if (outcome.accepted()) {
        arrivals_.on_arrival(now);
        last_seen_ms_ = core::to_ms(wall);
        timestamp_ms_ = sample_time(now, wall);
        const auto& header = exchange_.last_header();
        key_ = {header.request_id, header.time_s, header.time_ns, 0};
        // Values at the quality reported; while a return to `ok` is held, they wait for it.
        if (exchange_.state() == reported_state_) report_tags(now, false, key_);
    } else if (outcome.state_changed) {
        // Entering signature or length mismatch: the last values are to be reported as bad.
        timestamp_ms_ = core::to_ms(wall);
    }
    if (!(outcome.state_changed || clock_.state() != clock_before) || !settle(now)) {
        status_dirty_ = true;
    }
    return outcome;
}

bool ExchangeConsumer::settle(core::MonoTime now) {
    if (reported_current()) {
        pacer_.on_revert();
        return false;
    }
    if (!pacer_.on_change(now)) return false;
    report_change(now);
    return true;
}

void ExchangeConsumer::report_change(core::MonoTime now) {
    using core::exchange::ConsumeState;
    if (exchange_.state() != reported_state_) {
        if (exchange_.state() == ConsumeState::ok) {
            report_tags(now, false, key_);  // the last accepted datagram's values, good
        } else {
            report_quality_change(now);
        }
        reported_state_ = exchange_.state();
        // After the samples: a protocol that reports an exchange coming up (a Sparkplug
        // DBIRTH) then has its new values.
        northbound_.exchange_state(plan_, reported_state_);
    }
    report_status(now);
}

void ExchangeConsumer::on_tick(core::MonoTime now, core::WallTime wall, bool refresh_scan) {
    const auto state_before = exchange_.state();
    if (const auto changes = change_log_.flush(now)) log_summary(changes);
    if (exchange_.on_tick(now)) {
        log_state_change(state_before, now);
        // docs/protocol.md §4 rule 8: every tag of a stale exchange is reported again as
        // stale, keeping its last value; the timestamp says when it was found stale.
        timestamp_ms_ = core::to_ms(wall);
        settle(now);
        return;
    }
    // A change held within a period is reported as the exchange is at the period's end.
    if (pacer_.take_due(now)) {
        if (!reported_current()) report_change(now);
        return;
    }
    if (!reported_current()) return;
    if (refresh_scan) report_tags(now, false);
    // docs/mqtt-api.md "Exchange status": the status is reported on every state change, then
    // once a second (at this exchange's phase) while its counters move.
    if (status_dirty_ && exchange_.counters().received != last_status_received_ &&
        status_grid_.due(now)) {
        report_status(now, true);
    }
}

void ExchangeConsumer::republish(core::MonoTime now) {
    // Everything again, as it is now: nothing stays held.
    reported_state_ = exchange_.state();
    reported_clock_ = clock_.state();
    pacer_.on_revert();
    report_tags(now, true);
    // After the samples, as on a datagram: a Sparkplug node that learns here that the
    // exchange is up (as after a takeover) is born with them.
    northbound_.exchange_state(plan_, exchange_.state());
    report_status(now);
}

void ExchangeConsumer::report_quality_change(core::MonoTime now) {
    // Every unit that hears the exchange finds it after the same datagram: it is named after
    // that one.
    ++key_.change;
    report_tags(now, false, key_);
}

void ExchangeConsumer::report_tags(core::MonoTime now, bool all,
                                   std::optional<core::redundancy::SampleKey> key) {
    const auto quality = core::quality::quality_of(exchange_.state());
    if (!quality || !exchange_.has_image()) return;
    const auto image = exchange_.image();
    auto& samples = sample_buffer();
    for (std::size_t i = 0; i < plan_.tags.size(); ++i) {
        const auto& tag = plan_.tags[i];
        auto& filter = filters_[i];
        const auto raw = core::plan::decode_tag(image, tag.spec);
        // The deadband is of what is published: a scaled tag's engineering value.
        const auto published = core::plan::published_value(tag.spec, raw);
        if (!all && !filter.should_publish(published.value, *quality, now, tag.spec.deadband,
                                           tag.spec.refresh)) {
            continue;
        }
        filter.published(published.value, *quality, now);
        if (published.limit != core::plan::Limit::none) exchange_.count_beyond_raw_range();
        samples.push_back({i, raw});
    }
    if (samples.empty()) return;
    northbound_.tag_samples({plan_, *quality, timestamp_ms_, all, samples, key});
}

void ExchangeConsumer::report_status(core::MonoTime now, bool periodic) {
    northbound_.consumed_status(status());
    if (periodic) {
        status_grid_.reported_on_grid(now);
    } else {
        status_grid_.reported_off_grid(now);
    }
    last_status_received_ = exchange_.counters().received;
    reported_clock_ = clock_.state();
    status_dirty_ = false;
}

}  // namespace eip2mqtt::app
