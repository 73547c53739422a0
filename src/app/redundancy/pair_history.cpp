#include "eip2mqtt/app/redundancy/pair_history.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

namespace eip2mqtt::app::redundancy {
namespace {

/// How many due samples one call hands over at most: the loop has datagrams to read too.
constexpr std::size_t replay_per_call = 1000;

}  // namespace

PairHistory::PairHistory(PairHistoryOptions options, history::HistorySink& sink,
                         std::function<std::uint64_t()> backlog, const core::Clock& clock)
    : options_(options), sink_(sink), backlog_(std::move(backlog)), clock_(clock) {}

PairHistory::Exchange* PairHistory::find(const core::plan::ExchangePlan& plan) {
    const auto found = exchanges_.find(&plan);
    return found == exchanges_.end() ? nullptr : found->second.get();
}

void PairHistory::exchanges_changed(const ExchangeSet& running,
                                    std::span<const std::string> /*retired_topics*/) {
    const auto now = clock_.monotonic();
    const auto share = options_.max_bytes / std::max<std::size_t>(1, running.consumed.size());
    Exchanges kept;
    for (const auto* plan : running.consumed) {
        const auto bounds =
            core::redundancy::window_bounds(options_.takeover, plan->spec.period, share);
        const auto old = exchanges_.find(plan);
        if (old == exchanges_.end()) {
            kept.emplace(plan, std::make_unique<Exchange>(Exchange{
                                   plan, next_id_++, core::redundancy::SampleWindow(bounds)}));
            continue;
        }
        old->second->window.set_bounds(bounds, now);
        kept.insert(exchanges_.extract(old));
    }
    // What a stopped exchange had due goes with it (its plan dies after this call); each
    // sink's place moves back by what went before it.
    std::vector<Due> left;
    std::size_t json_place = 0, session_place = 0;
    for (std::size_t i = 0; i < due_.size(); ++i) {
        if (!kept.contains(due_[i].exchange->plan)) continue;
        if (i < next_due_) ++json_place;
        if (session_ && i < session_->next_due) ++session_place;
        left.push_back(std::move(due_[i]));
    }
    due_ = std::move(left);
    next_due_ = json_place;
    if (session_) session_->next_due = session_place;
    for (const auto& [plan, stopped] : exchanges_) acked_.forget(stopped->id);
    exchanges_ = std::move(kept);
}

void PairHistory::tag_samples(const SampleBatch& batch) {
    if (!batch.key) return;
    auto* exchange = find(batch.exchange);
    if (exchange == nullptr) return;
    counters_.window_overflow += exchange->window.record(
        *batch.key, clock_.monotonic(), batch.timestamp_ms, batch.quality, batch.samples);
}

std::uint64_t PairHistory::token_for(const SampleBatch& batch) {
    const auto* exchange = find(batch.exchange);
    if (exchange == nullptr || !batch.key) return 0;
    return acked_.published(exchange->id, *batch.key);
}

bool PairHistory::on_acknowledged(std::uint64_t token) {
    if (!core::redundancy::AckedWatermarks::owns(token)) return false;
    acked_.acknowledged(token);
    return true;
}

Watermarks PairHistory::watermarks() const {
    Watermarks out;
    for (const auto& [plan, exchange] : exchanges_) {
        if (const auto mark = acked_.watermark(exchange->id)) out.emplace(plan->spec.topic, *mark);
    }
    return out;
}

std::size_t PairHistory::take_due(Exchange& exchange, core::MonoTime now, bool& found) {
    const auto heard = heard_.find(exchange.plan->spec.topic);
    std::optional<core::redundancy::SampleKey> watermark;
    if (heard != heard_.end()) {
        watermark = heard->second;
        // Its renewals go on saying it until this unit has one of its own acknowledged.
        acked_.start_at(exchange.id, heard->second);
    }
    const auto start = exchange.window.after(watermark, now);
    found = start.watermark_found;
    for (auto i = start.first; i < exchange.window.size(); ++i) {
        due_.push_back({&exchange, exchange.window[i]});
    }
    return exchange.window.size() - start.first;
}

void PairHistory::took_over(core::MonoTime now) {
    due_.clear();
    next_due_ = 0;
    if (session_) session_->next_due = 0;
    acked_.clear();
    std::size_t samples = 0;
    std::size_t unmatched = 0;
    for (auto& [plan, exchange] : exchanges_) {
        bool found = false;
        const auto taken = take_due(*exchange, now, found);
        samples += taken;
        if (!found && taken > 0) ++unmatched;
    }
    // Oldest first across the exchanges; each exchange's own order is kept.
    std::stable_sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) {
        return a.sample.arrived < b.sample.arrived;
    });
    spdlog::info(
        "pair: taking over, {} sample(s) the leader had not had acknowledged go on _history{}{}",
        samples, session_ ? " and to the Sparkplug hosts, once the edge node is born" : "",
        unmatched == 0 ? std::string()
                       : " (" + std::to_string(unmatched) +
                             " exchange(s) without their watermark's sample in the window: "
                             "from the request ids on)");
    replay_some();
}

void PairHistory::stood_by() {
    // Its own watermarks are the newest it knows until it hears the next leader's: should it
    // lead again first, it replays only what came after them.
    for (auto& [topic, key] : watermarks()) heard_.insert_or_assign(topic, key);
    due_.clear();
    next_due_ = 0;
    if (session_) session_->next_due = 0;
    acked_.clear();
}

void PairHistory::add_session_sink(history::HistorySink& sink, std::function<bool()> ready,
                                   std::function<std::uint64_t()> backlog) {
    session_ = SessionSink{&sink, std::move(ready), std::move(backlog), 0};
}

void PairHistory::replay_some() {
    if (gate_ && !gate_()) return;
    std::size_t handed = 0;
    while (next_due_ < due_.size() && handed < replay_per_call &&
           (!backlog_ || backlog_() < options_.max_backlog)) {
        const auto& due = due_[next_due_++];
        const auto& sample = due.sample;
        const SampleBatch batch{*due.exchange->plan, sample.quality, sample.timestamp_ms, false,
                                sample.tags,         sample.key};
        if (sink_.replay(batch, acked_.published(due.exchange->id, sample.key))) {
            ++counters_.replayed;
        }
        ++handed;
    }
    replay_to_session();
    drop_replayed();
}

void PairHistory::replay_to_session() {
    if (!session_ || !session_->ready()) return;
    auto& session = *session_;
    std::size_t handed = 0;
    while (session.next_due < due_.size() && handed < replay_per_call &&
           session.backlog() < options_.max_backlog) {
        const auto& due = due_[session.next_due++];
        const auto& sample = due.sample;
        const SampleBatch batch{*due.exchange->plan, sample.quality, sample.timestamp_ms, false,
                                sample.tags,         sample.key};
        // No token: the watermarks are the JSON tree's alone.
        if (session.sink->replay(batch, 0)) ++session_replayed_;
        ++handed;
    }
}

void PairHistory::drop_replayed() {
    if (next_due_ < due_.size() || (session_ && session_->next_due < due_.size())) return;
    due_.clear();
    next_due_ = 0;
    if (session_) session_->next_due = 0;
}

}  // namespace eip2mqtt::app::redundancy
