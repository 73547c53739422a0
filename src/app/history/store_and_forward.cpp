#include "eip2mqtt/app/history/store_and_forward.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "eip2mqtt/adapters/history/sample_codec.hpp"

namespace eip2mqtt::app::history {
namespace {

using adapters::history::JournaledSample;
using adapters::history::JournalEntry;

std::uint64_t fnv1a(std::uint64_t hash, std::string_view bytes) {
    for (const unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
    return hash;
}

double seconds_since(core::MonoTime from, core::MonoTime now) {
    return std::chrono::duration<double>(now - from).count();
}

}  // namespace

std::uint64_t layout_fingerprint(const core::plan::ExchangePlan& plan) {
    std::uint64_t hash = 14695981039346656037ull;
    for (const auto& tag : plan.tags) {
        const auto& spec = tag.spec;
        hash = fnv1a(hash, spec.name);
        const char shape[4] = {
            static_cast<char>(spec.type), static_cast<char>(spec.address.byte & 0xff),
            static_cast<char>(spec.address.byte >> 8), static_cast<char>(spec.address.bit)};
        hash = fnv1a(hash, {shape, sizeof shape});
    }
    return hash;
}

StoreAndForward::StoreAndForward(std::unique_ptr<adapters::history::Journal> journal,
                                 StoreAndForwardOptions options, LinkProbe link, HistorySink& sink)
    : writer_(std::move(journal)),
      options_(options),
      first_(sink, std::move(link)),
      last_durable_(options_.clock->monotonic()) {}

StoreAndForward::~StoreAndForward() {
    // The writer commits durably what it is handed before it stops.
    writer_.append(pending_, true);
    try {
        delete_delivered();
    } catch (const std::exception& error) {
        spdlog::error("store and forward: the journal could not be closed cleanly: {}",
                      error.what());
    }
}

void StoreAndForward::exchanges_changed(const ExchangeSet& running, std::span<const std::string>) {
    exchanges_.clear();
    layouts_.clear();
    for (const auto* plan : running.consumed) {
        const auto layout = layout_fingerprint(*plan);
        exchanges_[plan->spec.name] = {plan, layout};
        layouts_[plan] = layout;
    }
}

void StoreAndForward::tag_samples(const SampleBatch& batch) {
    // A republish after a reconnect says nothing new: the samples it repeats went live or to
    // the journal when they came. A produced exchange's echo is what the writers sent.
    if (batch.all_tags || !journaling() ||
        batch.exchange.spec.direction != core::plan::Direction::consume) {
        return;
    }
    const auto known = layouts_.find(&batch.exchange);
    if (known == layouts_.end()) return;
    journaled_samples_.clear();
    for (const auto& sample : batch.samples) {
        journaled_samples_.push_back({static_cast<std::uint32_t>(sample.tag), sample.value});
    }
    auto& entry = pending_.emplace_back();
    entry.exchange = batch.exchange.spec.name;
    entry.layout = known->second;
    entry.timestamp_ms = batch.timestamp_ms;
    entry.quality = static_cast<std::uint8_t>(batch.quality);
    adapters::history::encode_samples(journaled_samples_, entry.samples);
    ++journaled_;
}

void StoreAndForward::on_connected(core::MonoTime now) {
    // What the client still holds of an earlier replay goes again after the reconnect and is
    // acknowledged then: the replay resumes after it, without sending anything twice.
    first_.start(now, false);
    replay_started_ = now;
    replay_started_with_ = replayed_;
    const auto entries = stats().journal.entries + pending_.size();
    if (entries > first_.outstanding()) {
        spdlog::info("store and forward: replaying {} journaled entries on _history", entries);
    }
}

void StoreAndForward::on_connected(HistorySink& sink, core::MonoTime now) {
    if (auto* replay = replay_of(sink)) replay->start(now, true);
}

void StoreAndForward::on_acknowledged(std::uint64_t id) {
    if (first_.acknowledge(id)) ++replayed_;
}

void StoreAndForward::on_acknowledged(HistorySink& sink, std::uint64_t id) {
    if (auto* replay = replay_of(sink)) replay->acknowledge(id);
}

SinkReplay* StoreAndForward::replay_of(HistorySink& sink) {
    for (auto& replay : extra_) {
        if (&replay->sink() == &sink) return replay.get();
    }
    return nullptr;
}

void StoreAndForward::on_tick(core::MonoTime now) {
    const bool durable = now - last_durable_ >= options_.fsync_interval;
    if (!pending_.empty() || durable) writer_.append(pending_, durable);
    if (durable) last_durable_ = now;
    try {
        delete_delivered();
        if (first_.active()) replay_some(first_, now, true);
        for (auto& replay : extra_) {
            if (replay->active()) {
                replay_some(*replay, now, false);
            } else {
                replay->note_live(now, writer_.last_id());
            }
        }
    } catch (const std::exception& error) {
        fail("the journal failed", error);
    }
    if (const auto count = failure_log_.flush(now)) {
        spdlog::error("store and forward: {} more journal failures", count);
    }
}

void StoreAndForward::delete_delivered() {
    auto through = first_.through();
    for (const auto& replay : extra_) through = std::min(through, replay->through());
    if (through > deleted_through_) {
        writer_.with([&](auto& journal) { journal.remove_through(through); });
        deleted_through_ = through;
    }
}

void StoreAndForward::replay_some(SinkReplay& replay, core::MonoTime now, bool first) {
    const auto room = replay.room(now, options_.replay_rate);
    if (room == 0) return;
    const auto deadline = options_.clock->monotonic() + options_.replay_budget;
    // Asked before the read: when nothing waits for the writer then, the read sees it all.
    const bool all_written = pending_.empty() && writer_.idle();
    const auto entries = writer_.with([&](auto& journal) {
        return journal.oldest(std::min(room, replay.pace()), replay.cursor());
    });
    if (entries.empty() && replay.outstanding() == 0 && all_written) {
        replay.finish();
        if (first && replayed_ > replay_started_with_) {
            spdlog::info("store and forward: {} journaled entries replayed in {:.1f} s",
                         replayed_ - replay_started_with_, seconds_since(replay_started_, now));
        }
        return;
    }
    std::vector<std::uint64_t> unusable;
    std::size_t handed = 0;
    bool out_of_time = false;
    for (const auto& entry : entries) {
        if (handed > 0 && options_.clock->monotonic() >= deadline) {
            out_of_time = true;  // the rest at the next tick: the datagrams go first
            break;
        }
        ++handed;
        if (!replay_entry(replay, entry)) {
            replay.handed(entry.id, false);
            unusable.push_back(entry.id);
        }
    }
    replay.paced(handed, out_of_time);
    // At once: another sink's replay must not meet them (and count them) again.
    if (!unusable.empty()) writer_.with([&](auto& journal) { journal.remove(unusable); });
}

std::string StoreAndForward::unusable(const JournalEntry& entry) {
    const auto known = exchanges_.find(entry.exchange);
    if (known == exchanges_.end()) return "no such exchange any more";
    if (known->second.layout != entry.layout) return "its tags changed since";
    auto decoded = adapters::history::decode_samples(entry.samples);
    if (!decoded) return decoded.error();
    const auto& plan = *known->second.plan;
    samples_.clear();
    for (const auto& sample : decoded.value()) {
        if (sample.tag >= plan.tags.size()) return "a tag index beyond the exchange's tags";
        samples_.push_back({sample.tag, sample.value});
    }
    return {};
}

bool StoreAndForward::replay_entry(SinkReplay& replay, const JournalEntry& entry) {
    if (const auto problem = unusable(entry); !problem.empty()) {
        ++discarded_;
        if (const auto count = discard_log_.record(options_.clock->monotonic())) {
            spdlog::warn(
                "store and forward: journaled entries of exchange {} cannot be replayed ({}); "
                "deleted ({} since the last report)",
                entry.exchange, problem, count);
        }
        return false;
    }
    const auto& plan = *exchanges_.find(entry.exchange)->second.plan;
    const SampleBatch batch{plan, static_cast<core::quality::Quality>(entry.quality),
                            entry.timestamp_ms, false, samples_};
    replay.handed(entry.id, replay.sink().replay(batch, entry.id));
    return true;
}

void StoreAndForward::fail(const char* what, const std::exception& error) {
    ++failures_;
    if (const auto count = failure_log_.record(options_.clock->monotonic())) {
        spdlog::error("store and forward: {}: {} ({} since the last report); live data goes on",
                      what, error.what(), count);
    }
}

HistoryStats StoreAndForward::stats() {
    HistoryStats stats;
    try {
        stats.journal = writer_.with([](auto& journal) { return journal.stats(); });
    } catch (const std::exception& error) {
        fail("the journal's figures could not be read", error);
    }
    stats.journaled = journaled_;
    stats.replayed = replayed_;
    stats.discarded = discarded_;
    stats.failures = failures_ + writer_.failures();
    stats.replaying = first_.active();
    for (const auto& replay : extra_) stats.replaying = stats.replaying || replay->active();
    stats.taken_at_ms = options_.clock->wall_ms();
    return stats;
}

}  // namespace eip2mqtt::app::history
