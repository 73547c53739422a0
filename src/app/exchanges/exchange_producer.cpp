#include "eip2mqtt/app/exchanges/exchange_producer.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app {
namespace {

using namespace std::chrono_literals;

// While saves fail, how often the image is saved again without a write asking for it.
constexpr auto save_retry_interval = 1s;

std::vector<std::byte> restored_data(const std::optional<ImageHandover>& handover,
                                     const adapters::state::ImageFile& file) {
    if (handover) return handover->data;
    return file.loaded().value_or(std::vector<std::byte>{});
}

std::int64_t to_ms(core::WallTime wall) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count();
}

}  // namespace

ExchangeProducer::ExchangeProducer(core::plan::ExchangePlan plan,
                                   adapters::udp::Endpoint destination,
                                   ProducerScheduler& scheduler,
                                   adapters::state::ImagePersister& persister,
                                   Northbound& northbound, ImageSaveTotals& totals,
                                   std::optional<ImageHandover> handover)
    : plan_(std::make_shared<const core::plan::ExchangePlan>(std::move(plan))),
      destination_(destination),
      scheduler_(scheduler),
      persister_(persister),
      persist_key_(
          persister.attach([this](const std::optional<std::string>& error) { on_saved(error); })),
      northbound_(northbound),
      totals_(totals),
      file_(handover ? handover->file : persister.open(*plan_)),
      image_(*plan_, restored_data(handover, *file_)),
      datagram_(core::wire::header_size + plan_->length) {
    limiters_.reserve(plan_->tags.size());
    for (const auto& tag : plan_->tags) limiters_.emplace_back(tag.spec.max_writes_per_s());
    spdlog::info("exchange {}: producing to {} every {} ms, {} image", plan_->spec.name,
                 adapters::udp::to_string(destination_), plan_->spec.period.count(),
                 handover            ? "running"
                 : image_.restored() ? "restored"
                                     : "initial");
    // Written at once unless the file holds exactly this image in the slotted format, so that
    // the file's blocks exist before the disk fills up. A handed-over image is written all the
    // same: the file may hold writes the reload cancelled, or have been removed.
    saved_ = !handover && file_->in_place();
    if (!saved_) request_save();
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

std::size_t ExchangeProducer::cancel_queued_writes(std::optional<std::string_view> error) {
    std::vector<std::uint64_t> ids;
    image_.discard_pending(ids);
    if (ids.empty()) return 0;
    for (const auto id : ids) {
        const auto reply = take_reply(id);
        if (reply && error) northbound_.write_result(*reply, error);
    }
    if (error) {
        spdlog::warn("exchange {}: {} queued write(s) answered \"{}\": never produced",
                     plan_->spec.name, ids.size(), *error);
    } else {
        spdlog::warn(
            "exchange {}: {} queued write(s) left to the unit that took the lead: never "
            "produced here",
            plan_->spec.name, ids.size());
    }
    // Saved ahead of a production that will not come: the file gets the produced image back.
    if (ids.front() <= saved_through_) {
        persister_.save(adapters::state::ImagePersister::unattended, file_, image_.data());
    }
    return ids.size();
}

std::vector<WriteRequest> ExchangeProducer::take_queued_writes() {
    std::vector<core::write::WriteBatch> batches;
    image_.take_pending(batches);
    std::vector<WriteRequest> taken;
    if (batches.empty()) return taken;
    for (auto& batch : batches) {
        auto reply = take_reply(batch.id);
        if (!reply) continue;
        // Answered on `{set topic}/result`, or on its response topic (PairWrites tells them so).
        auto target = reply->topic;
        if (target.ends_with("/result")) target.resize(target.size() - 7);
        taken.push_back({std::move(*reply),
                         std::move(target),
                         ExchangeWrite{plan_.get(), std::move(batch.writes)},
                         {}});
    }
    spdlog::warn(
        "exchange {}: {} queued write(s) left to the unit that leads next: never produced here",
        plan_->spec.name, batches.size());
    if (batches.front().id <= saved_through_) {
        persister_.save(adapters::state::ImagePersister::unattended, file_, image_.data());
    }
    return taken;
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
    // Until a save succeeds, a write is saved before it may be produced.
    if (!saved_) request_save();
    return std::nullopt;
}

std::span<const std::byte> ExchangeProducer::produce(core::WallTime wall) {
    carried_.clear();
    const auto through = saved_ ? core::exchange::ProducedImage::no_limit : saved_through_;
    const auto size = image_.produce(wall, datagram_, carried_, through);
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
        if (on_image_changed_) on_image_changed_(*this);
    }
    counters_.writes_applied += carried_.size();
    // docs/mqtt-api.md "Results": a write's result is reported once the datagram carrying it was
    // sent and the image carrying it is saved. Those saved ahead are answered now; the others
    // wait for the save their change asks for, or for the one under way, which may hold the
    // value they wrote (a write that changed nothing).
    const auto ahead = std::find_if(carried_.begin(), carried_.end(),
                                    [&](std::uint64_t id) { return id > saved_through_; });
    report_results(std::span(carried_.begin(), ahead));
    const std::span waiting(ahead, carried_.end());
    if ((changed && saved_) || (!waiting.empty() && (save_in_flight_ || save_again_))) {
        unsaved_.insert(unsaved_.end(), waiting.begin(), waiting.end());
        request_save();
        return;
    }
    report_results(waiting);
}

bool ExchangeProducer::follow_image(std::span<const std::byte> data) {
    if (!image_.adopt(data)) return false;
    // What a restart of this unit produces too, should it lead then.
    request_save();
    return true;
}

void ExchangeProducer::request_save() {
    if (save_in_flight_) {
        save_again_ = true;
        return;
    }
    save_again_ = false;
    save_in_flight_ = true;
    saving_.swap(unsaved_);
    unsaved_.clear();
    saving_through_ = image_.project(projection_);
    persister_.save(persist_key_, file_, projection_);
}

void ExchangeProducer::on_saved(const std::optional<std::string>& error) {
    save_in_flight_ = false;
    const auto answered = std::move(saving_);
    saving_.clear();
    if (error) {
        on_save_failed(*error, answered);
    } else {
        saved_through_ = std::max(saved_through_, saving_through_);
        const bool changed = !saved_;
        saved_ = true;
        if (!save_error_.empty()) {
            spdlog::info("exchange {}: image saved again to {}", plan_->spec.name, file_->path());
            save_error_.clear();
            save_log_.reset();
        }
        report_results(answered);
        if (changed) report_status();
    }
    if (save_again_) request_save();
}

void ExchangeProducer::on_save_failed(const std::string& error,
                                      const std::vector<std::uint64_t>& sent) {
    ++counters_.save_failures;
    ++totals_.failures;
    saved_ = false;
    retry_at_.reset();
    for (const auto id : sent) {
        auto reply = take_reply(id);
        if (!reply) continue;
        answer_accepted(id, std::move(*reply), error);
        ++totals_.writes_sent_unsaved;
    }
    // Queued writes that this save held wait on no other: they are never produced.
    std::vector<std::uint64_t> refused;
    image_.discard_pending(saved_through_, saving_through_, refused);
    const auto answer = "not saved: " + error;
    for (const auto id : refused) {
        const auto reply = take_reply(id);
        if (!reply) continue;
        northbound_.write_result(*reply, answer);
        ++totals_.writes_not_saved;
    }
    const bool changed = error != save_error_;
    save_error_ = error;
    const auto count = save_log_.record(std::chrono::steady_clock::now());
    if (count == 1) {
        spdlog::error(
            "exchange {}: cannot save its image ({}): {} write(s) sent unsaved, {} queued "
            "write(s) refused; until a save succeeds, each write is saved before it is produced",
            plan_->spec.name, error, sent.size(), refused.size());
    } else if (count > 1) {
        spdlog::error("exchange {}: {} image saves failed in the last {} s, the last one: {}",
                      plan_->spec.name, count, save_log_.interval().count(), error);
    }
    if (changed) report_status();
}

void ExchangeProducer::report_results(std::span<const std::uint64_t> write_ids) {
    for (const auto id : write_ids) {
        if (auto reply = take_reply(id)) answer_accepted(id, std::move(*reply), std::nullopt);
    }
}

void ExchangeProducer::answer_accepted(std::uint64_t write_id, WriteReply reply,
                                       std::optional<std::string> unsaved) {
    auto answer = [&northbound = northbound_, reply, unsaved = std::move(unsaved)] {
        if (unsaved) return northbound.write_result_unsaved(reply, *unsaved);
        northbound.write_result(reply, std::nullopt);
    };
    if (!answer_gate_) return answer();
    answer_gate_(*this, write_id, reply, std::move(answer));
}

std::optional<WriteReply> ExchangeProducer::take_reply(std::uint64_t write_id) {
    auto node = replies_.extract(write_id);
    if (node.empty()) return std::nullopt;
    return std::move(node.mapped());
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
    if (!saved_ && !save_in_flight_) {
        if (!retry_at_) {
            retry_at_ = now + save_retry_interval;
        } else if (now >= *retry_at_) {
            retry_at_.reset();
            request_save();
        }
    }
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
    status.counters = counters_;
    status.writes_pending = image_.pending();
    status.saved = saved_;
    status.save_error = save_error_;
    northbound_.produced_status(*plan_, status);
}

void ExchangeProducer::republish(core::WallTime wall) {
    report_echo(wall, true);
    report_status();
}

}  // namespace eip2mqtt::app
