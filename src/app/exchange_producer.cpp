#include "eip2mqtt/app/exchange_producer.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app {
namespace {

std::vector<std::byte> restore(const adapters::state::ImagePersister& persister,
                               const core::plan::ExchangePlan& plan) {
    auto saved = persister.load(plan);
    return saved ? std::move(*saved) : std::vector<std::byte>{};
}

std::int64_t to_ms(core::WallTime wall) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count();
}

}  // namespace

ExchangeProducer::ExchangeProducer(core::plan::ExchangePlan plan,
                                   adapters::udp::Endpoint destination,
                                   ProducerScheduler& scheduler,
                                   adapters::state::ImagePersister& persister,
                                   Northbound& northbound)
    : plan_(std::make_shared<const core::plan::ExchangePlan>(std::move(plan))),
      destination_(destination),
      scheduler_(scheduler),
      persister_(persister),
      persist_key_(persister.attach(
          [this](bool ok, const std::vector<std::uint64_t>& ids) { on_saved(ok, ids); })),
      northbound_(northbound),
      image_(*plan_, restore(persister, *plan_)),
      datagram_(core::wire::header_size + plan_->length) {
    limiters_.reserve(plan_->tags.size());
    for (const auto& tag : plan_->tags) limiters_.emplace_back(tag.spec.max_writes_per_s());
    spdlog::info("exchange {}: producing to {} every {} ms, {} image", plan_->spec.name,
                 adapters::udp::to_string(destination_), plan_->spec.period.count(),
                 image_.restored() ? "restored" : "initial");
}

ExchangeProducer::~ExchangeProducer() {
    stop();
    persister_.detach(persist_key_);
}

void ExchangeProducer::start(core::MonoTime start, std::size_t index, std::size_t count) {
    id_ = scheduler_.add(
        *this, core::exchange::ProductionSchedule(start, plan_->spec.period, index, count));
    // `_status` at the producer's own phase of the second, as its sends are spread (StatusGrid).
    if (count > 0) status_grid_.start(start, index, count);
}

void ExchangeProducer::stop() {
    if (id_) scheduler_.remove(*id_);
    id_.reset();
}

std::size_t ExchangeProducer::cancel_queued_writes(std::string_view error) {
    std::vector<std::uint64_t> ids;
    image_.discard_pending(ids);
    if (ids.empty()) return 0;
    for (const auto id : ids) {
        const auto it = replies_.find(id);
        if (it == replies_.end()) continue;
        northbound_.write_result(it->second, error);
        replies_.erase(it);
    }
    spdlog::warn("exchange {}: {} queued write(s) answered \"{}\": never produced",
                 plan_->spec.name, ids.size(), error);
    return ids.size();
}

std::optional<core::write::WriteRejection> ExchangeProducer::stage(
    std::vector<core::write::TagWrite> writes, WriteReply reply, core::MonoTime now) {
    for (const auto& write : writes) {
        const auto& tag = plan_->tags[write.tag_index].spec;
        if (!limiters_[write.tag_index].allow(now)) {
            return core::write::WriteRejection{core::write::WriteError::rate_limited,
                                               fmt::format("{}: more than {} writes per second",
                                                           tag.name, tag.max_writes_per_s())};
        }
    }
    const auto id = next_write_id_++;
    if (!image_.stage({id, std::move(writes)})) {
        return core::write::WriteRejection{
            core::write::WriteError::queue_full,
            "write queue of exchange " + plan_->spec.name + " is full; try again"};
    }
    replies_.emplace(id, std::move(reply));
    return std::nullopt;
}

std::span<const std::byte> ExchangeProducer::produce(core::WallTime wall) {
    carried_.clear();
    const auto size = image_.produce(wall, datagram_, carried_);
    return std::span(datagram_.data(), size);
}

void ExchangeProducer::on_sent(bool sent, core::WallTime wall) {
    if (sent) {
        ++counters_.sent;
        last_sent_ = wall;
    } else {
        ++counters_.send_errors;
    }
    if (sent == failing_) {
        failing_ = !sent;
        if (failing_) {
            spdlog::warn("exchange {}: cannot send to {}; paused until sends succeed again",
                         plan_->spec.name, adapters::udp::to_string(destination_));
        } else {
            spdlog::info("exchange {}: sending again", plan_->spec.name);
        }
        report_status();
    }

    const bool changed = image_.dirty();
    if (changed) {
        image_.clear_dirty();
        report_echo(wall, false);
    }
    counters_.writes_applied += carried_.size();
    // docs/mqtt-api.md "Results": a write's result is reported once the datagram carrying it was
    // sent and the image carrying it is saved. The save runs off the loop; a write that changed
    // nothing still waits for a save under way, which may hold the value it wrote.
    if (changed || (saves_in_flight_ > 0 && !carried_.empty())) {
        ++saves_in_flight_;
        persister_.save(persist_key_, plan_, image_.data(), carried_);
        return;
    }
    report_results(carried_);
}

void ExchangeProducer::on_saved(bool ok, const std::vector<std::uint64_t>& write_ids) {
    if (saves_in_flight_ > 0) --saves_in_flight_;
    if (!ok) ++counters_.persist_failures;
    report_results(write_ids);
}

void ExchangeProducer::report_results(const std::vector<std::uint64_t>& write_ids) {
    for (const auto id : write_ids) {
        const auto it = replies_.find(id);
        if (it == replies_.end()) continue;
        northbound_.write_result(it->second, std::nullopt);
        replies_.erase(it);
    }
}

void ExchangeProducer::report_echo(core::WallTime wall, bool all) {
    const auto data = image_.data();
    auto& samples = sample_buffer();
    for (std::size_t i = 0; i < plan_->tags.size(); ++i) {
        const auto& tag = plan_->tags[i].spec;
        const auto value = core::plan::decode_value(data, tag.type, tag.address);
        if (!all && echoed_.size() == data.size()) {
            const auto old = core::plan::decode_value(echoed_, tag.type, tag.address);
            if (core::plan::same_value(old, value)) continue;
        }
        samples.push_back({i, value});
    }
    echoed_.assign(data.begin(), data.end());
    if (samples.empty()) return;
    northbound_.tag_samples({*plan_, core::quality::Quality::good, to_ms(wall), all, samples});
}

void ExchangeProducer::on_tick(core::MonoTime now) {
    // docs/mqtt-api.md "Exchange status": at most once a second while its counters move.
    if (counters_.sent == last_status_sent_) return;
    if (!status_grid_.due(now)) return;
    status_grid_.reported_on_grid(now);
    report_status();
}

void ExchangeProducer::report_status() {
    last_status_sent_ = counters_.sent;
    ProducedStatus status;
    status.paused = failing_;
    status.request_id = image_.next_request_id();
    status.sent = counters_.sent;
    status.send_errors = counters_.send_errors;
    status.skipped_deadlines = counters_.skipped_deadlines;
    status.writes_applied = counters_.writes_applied;
    status.writes_pending = image_.pending();
    northbound_.produced_status(*plan_, status);
}

void ExchangeProducer::republish(core::WallTime wall) {
    report_echo(wall, true);
    report_status();
}

}  // namespace eip2mqtt::app
