#include "eip2mqtt/app/exchanges/exchange_producer.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app {
namespace {

std::vector<std::byte> restored_data(const std::optional<ImageHandover>& handover,
                                     const adapters::state::ImageFile& file) {
    if (handover) return handover->data;
    return file.loaded().value_or(std::vector<std::byte>{});
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
      northbound_(northbound),
      saves_{persister,
             persister.attach([this](const std::optional<std::string>& error) { on_saved(error); }),
             handover ? handover->file : persister.open(*plan_), core::ThrottledLog{}},
      totals_(totals),
      image_(*plan_, restored_data(handover, *saves_.file)),
      // Written at once unless the file holds exactly this image in the slotted format, so that
      // the file's blocks exist before the disk fills up. A handed-over image is written all the
      // same: the file may hold writes the reload cancelled, or have been removed.
      save_(!handover && saves_.file->in_place()),
      outgoing_{std::vector<std::byte>(core::wire::header_size + plan_->length), {}},
      configured_at_(scheduler.clock().wall()) {
    writes_.limiters.reserve(plan_->tags.size());
    for (const auto& tag : plan_->tags) writes_.limiters.emplace_back(tag.spec.max_writes_per_s());
    spdlog::info("exchange {}: producing to {} every {} ms, {} image", plan_->spec.name,
                 adapters::udp::to_string(destination_), plan_->spec.period.count(),
                 handover            ? "running"
                 : image_.restored() ? "restored"
                                     : "initial");
    if (!save_.saved()) request_save();
}

ExchangeProducer::~ExchangeProducer() {
    stop();
    saves_.persister.detach(saves_.key);
}

void ExchangeProducer::start(core::MonoTime start, std::size_t index, std::size_t count) {
    id_ = scheduler_.add(
        *this, core::exchange::ProductionSchedule(start, plan_->spec.period, index, count));
    // `_status` at the producer's own phase of the second, as its sends are spread (StatusGrid).
    if (count > 0) status_.grid.start(start, index, count);
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
    unsave_queued(ids.front());
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
        // Answered on `{set topic}/result`, or on its response topic (the role tells them so).
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
    unsave_queued(batches.front().id);
    return taken;
}

void ExchangeProducer::unsave_queued(std::uint64_t first_taken) {
    // Saved ahead of a production that will not come: the file gets the produced image back.
    if (!save_.holds(first_taken)) return;
    saves_.persister.save(adapters::state::ImagePersister::unattended, saves_.file, image_.data());
}

std::optional<core::write::WriteRejection> ExchangeProducer::stage(
    std::vector<core::write::TagWrite> writes, WriteReply reply, core::MonoTime now) {
    for (const auto& write : writes) {
        const auto& tag = plan_->tags[write.tag_index].spec;
        if (!writes_.limiters[write.tag_index].allow(now)) {
            return core::write::WriteRejection{core::write::WriteError::rate_limited,
                                               fmt::format("{}: more than {} writes per second",
                                                           tag.name, tag.max_writes_per_s())};
        }
    }
    const auto id = writes_.next_id++;
    if (!image_.stage({id, std::move(writes)})) {
        return core::write::WriteRejection{
            core::write::WriteError::queue_full,
            "write queue of exchange " + plan_->spec.name + " is full; try again"};
    }
    writes_.replies.emplace(id, std::move(reply));
    // Until a save succeeds, a write is saved before it may be produced.
    if (save_.on_staged()) request_save();
    return std::nullopt;
}

std::span<const std::byte> ExchangeProducer::produce(core::WallTime wall) {
    outgoing_.carried.clear();
    const auto size =
        image_.produce(wall, outgoing_.datagram, outgoing_.carried, save_.produce_through());
    return std::span(outgoing_.datagram.data(), size);
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
        role_->image_changed(*this);
    }
    counters_.writes_applied += outgoing_.carried.size();
    // docs/mqtt-api.md "Results": a write's result is reported once the datagram carrying it was
    // sent and the image carrying it is saved (SaveThenAnswer::on_sent).
    const auto answer = save_.on_sent(outgoing_.carried, changed);
    report_results(answer.answer);
    if (answer.save) request_save();
}

bool ExchangeProducer::follow_image(std::span<const std::byte> data) {
    if (!image_.adopt(data)) return false;
    // What a restart of this unit produces too, should it lead then.
    request_save();
    return true;
}

void ExchangeProducer::request_save() {
    if (const auto bytes = save_.request(image_)) {
        saves_.persister.save(saves_.key, saves_.file, *bytes);
    }
}

void ExchangeProducer::on_saved(const std::optional<std::string>& error) {
    const auto saved = save_.on_saved(error);
    if (error) {
        on_save_failed(saved);
    } else {
        if (saved.recovered) {
            spdlog::info("exchange {}: image saved again to {}", plan_->spec.name,
                         saves_.file->path());
            saves_.log.reset();
        }
        report_results(saved.answered);
        if (saved.status_changed) report_status();
    }
    if (save_.again()) request_save();
}

void ExchangeProducer::on_save_failed(const core::exchange::SaveThenAnswer::Saved& saved) {
    const auto& error = save_.error();
    ++counters_.save_failures;
    ++totals_.failures;
    for (const auto id : saved.answered) {
        auto reply = take_reply(id);
        if (!reply) continue;
        answer_accepted(id, std::move(*reply), error);
        ++totals_.writes_sent_unsaved;
    }
    // Queued writes that this save held wait on no other: they are never produced.
    std::vector<std::uint64_t> refused;
    image_.discard_pending(saved.refuse_after, saved.refuse_through, refused);
    const auto answer = "not saved: " + error;
    for (const auto id : refused) {
        const auto reply = take_reply(id);
        if (!reply) continue;
        northbound_.write_result(*reply, answer);
        ++totals_.writes_not_saved;
    }
    const auto count = saves_.log.record(scheduler_.clock().monotonic());
    if (count == 1) {
        spdlog::error(
            "exchange {}: cannot save its image ({}): {} write(s) sent unsaved, {} queued "
            "write(s) refused; until a save succeeds, each write is saved before it is produced",
            plan_->spec.name, error, saved.answered.size(), refused.size());
    } else if (count > 1) {
        spdlog::error("exchange {}: {} image saves failed in the last {} s, the last one: {}",
                      plan_->spec.name, count, saves_.log.interval().count(), error);
    }
    if (saved.status_changed) report_status();
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
    role_->answer_write(*this, write_id, reply, std::move(answer));
}

std::optional<WriteReply> ExchangeProducer::take_reply(std::uint64_t write_id) {
    auto node = writes_.replies.extract(write_id);
    if (node.empty()) return std::nullopt;
    return std::move(node.mapped());
}

void ExchangeProducer::report_echo(core::WallTime wall, bool all) {
    const auto data = image_.data();
    auto& samples = sample_buffer();
    for (std::size_t i = 0; i < plan_->tags.size(); ++i) {
        const auto& tag = plan_->tags[i].spec;
        const auto value = core::plan::decode_tag(data, tag);
        if (!all && echoed_.size() == data.size()) {
            const auto old = core::plan::decode_tag(echoed_, tag);
            if (core::plan::same_value(old, value)) continue;
        }
        samples.push_back({i, value});
    }
    echoed_.assign(data.begin(), data.end());
    if (samples.empty()) return;
    northbound_.tag_samples(
        {*plan_, core::quality::Quality::good, core::to_ms(wall), all, samples});
}

void ExchangeProducer::on_tick(core::MonoTime now) {
    if (save_.on_tick(now)) request_save();
    // docs/mqtt-api.md "Exchange status": at most once a second while its counters move.
    if (counters_.sent == status_.last_sent) return;
    if (!status_.grid.due(now)) return;
    status_.grid.reported_on_grid(now);
    report_status();
}

ProducedStatus ExchangeProducer::status() const {
    ProducedStatus status;
    status.paused = failing_;
    status.request_id = image_.next_request_id();
    status.counters = counters_;
    status.writes_pending = image_.pending();
    status.saved = save_.saved();
    status.save_error = save_.error();
    return status;
}

void ExchangeProducer::report_status() {
    status_.last_sent = counters_.sent;
    northbound_.produced_status(*plan_, status());
}

void ExchangeProducer::republish(core::WallTime wall) {
    report_echo(wall, true);
    report_status();
}

}  // namespace eip2mqtt::app
