// The exchanges' life cycle (docs/operations.md, Reload): a reload keeps the
// exchanges whose plan is unchanged, with their sequence, image and sockets, starts new and
// changed ones and stops removed and changed ones; no write is left without an answer.

#include "eip2mqtt/app/exchanges/exchanges.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <utility>

#include "eip2mqtt/core/plan/plan_diff.hpp"

namespace eip2mqtt::app {
namespace {

/// The image of the producer that `plan` replaces, when a reload changes its exchange but not
/// the layout of its image: the running image goes on, whatever its file holds.
std::optional<ImageHandover> handover_for(
    const core::plan::ExchangePlan& plan,
    std::span<const std::unique_ptr<ExchangeProducer>> old_producers) {
    for (const auto& producer : old_producers) {
        if (!producer || producer->plan().spec.name != plan.spec.name) continue;
        if (adapters::state::layout_fingerprint(producer->plan()) !=
            adapters::state::layout_fingerprint(plan)) {
            return std::nullopt;
        }
        return producer->hand_over();
    }
    return std::nullopt;
}

}  // namespace

Exchanges::Exchanges(boost::asio::any_io_executor loop, ExchangesOptions options,
                     Northbound& northbound, ImageSaveTotals& totals, const core::Clock& clock)
    : loop_(std::move(loop)),
      options_(std::move(options)),
      northbound_(northbound),
      totals_(totals),
      clock_(clock),
      image_store_(options_.state_dir),
      router_(clock) {}

Exchanges::~Exchanges() = default;

ApplyReport Exchanges::apply(std::vector<core::plan::ExchangePlan> plans, core::MonoTime now,
                             core::WallTime wall) {
    // Saves still under way must reach the disk, and their writes their results, before an
    // image is handed over or read.
    if (persister_) persister_->flush();
    const auto diff = core::plan::diff_plans(running_plans(), plans);
    ApplyReport report;
    // Named for the log before the plans move into the exchanges.
    report.changes = core::plan::describe_diff(diff, running_plans(), plans);

    auto old_consumers = std::move(consumers_);
    auto old_producers = std::move(producers_);
    consumers_.clear();
    producers_.clear();
    const auto old_consumer_count = old_consumers.size();
    const auto old_plans_name = [&](std::size_t index) -> const std::string& {
        return index < old_consumer_count
                   ? old_consumers[index]->plan().spec.name
                   : old_producers[index - old_consumer_count]->plan().spec.name;
    };

    for (const auto index : diff.stopped) report.stopped.push_back(old_plans_name(index));
    Built built;
    for (std::size_t i = 0; i < plans.size(); ++i) {
        auto& plan = plans[i];
        if (const auto from = diff.kept_from[i]) {
            report.kept.push_back(plan.spec.name);
            if (*from < old_consumer_count) {
                consumers_.push_back(std::move(old_consumers[*from]));
            } else {
                producers_.push_back(std::move(old_producers[*from - old_consumer_count]));
            }
            continue;
        }
        report.started.push_back(plan.spec.name);
        if (plan.spec.direction == core::plan::Direction::consume) {
            consumers_.push_back(
                std::make_unique<ExchangeConsumer>(std::move(plan), northbound_, clock_));
            built.consumers.push_back(consumers_.back().get());
            continue;
        }
        auto handover = handover_for(plan, old_producers);
        producers_.push_back(make_producer(std::move(plan), std::move(handover)));
        built.producers.push_back(producers_.back().get());
    }
    report.cancelled_writes = cancel_stopped(diff.stopped, old_consumer_count, old_producers);
    report.cleared_topics = diff.cleared.size();
    // The northbounds forget retired exchanges (retained topics cleared) and learn the new ones
    // (the JSON tree's `set` subscriptions), before the stopped ones die with old_*.
    northbound_.exchanges_changed(running(), diff.cleared);
    router_.set_consumers(consumers_);
    router_.set_followed(producers_, *options_.role);
    by_handle_.clear();
    for (const auto& producer : producers_) by_handle_.emplace(&producer->plan(), producer.get());
    start_built(built, now, wall);
    return report;
}

std::size_t Exchanges::cancel_stopped(std::span<const std::size_t> stopped,
                                      std::size_t consumer_count,
                                      std::span<std::unique_ptr<ExchangeProducer>> old_producers) {
    // A stopped producer's queued writes, which it will never produce, are answered now: never
    // silence. (Those its last datagrams carried got their results from the flush in apply.)
    // Stopped consumers need nothing: they die with the old consumers.
    std::size_t cancelled = 0;
    for (const auto index : stopped) {
        if (index < consumer_count) continue;
        auto& producer = old_producers[index - consumer_count];
        producer->stop();
        cancelled += producer->cancel_queued_writes("reloaded");
    }
    return cancelled;
}

void Exchanges::start_built(const Built& built, core::MonoTime now, core::WallTime wall) {
    for (std::size_t i = 0; i < built.consumers.size(); ++i) {
        built.consumers[i]->set_status_phase(i, built.consumers.size());
    }
    if (!started_) return;
    for (std::size_t i = 0; i < built.producers.size(); ++i) {
        built.producers[i]->start(now, i, built.producers.size());
        built.producers[i]->republish(wall);
    }
    for (auto* consumer : built.consumers) consumer->republish(now);
}

std::unique_ptr<ExchangeProducer> Exchanges::make_producer(core::plan::ExchangePlan plan,
                                                           std::optional<ImageHandover> handover) {
    const auto destination = adapters::udp::resolve_endpoint(plan.spec.destination, options_.port);
    if (!destination) {
        throw std::runtime_error("exchange " + plan.spec.name + ": cannot resolve destination " +
                                 plan.spec.destination);
    }
    if (!sender_) {
        sender_ = std::make_unique<adapters::udp::Sender>(loop_, options_.sender);
        scheduler_ = std::make_unique<ProducerScheduler>(loop_, *sender_, clock_);
        scheduler_->set_role(*options_.role);
        persister_ = std::make_unique<adapters::state::ImagePersister>(image_store_, loop_);
    }
    auto producer =
        std::make_unique<ExchangeProducer>(std::move(plan), *destination, *scheduler_, *persister_,
                                           northbound_, totals_, std::move(handover));
    producer->set_role(*options_.role);
    return producer;
}

void Exchanges::start(core::MonoTime now) {
    started_ = true;
    for (std::size_t i = 0; i < producers_.size(); ++i) {
        producers_[i]->start(now, i, producers_.size());
    }
}

void Exchanges::stop() {
    for (auto& producer : producers_) producer->stop();
    // The last saves reach the disk, and their write results the northbounds.
    if (persister_) persister_->flush();
    for (const auto& producer : producers_) {
        if (producer->saved()) continue;
        spdlog::error(
            "exchange {}: stopping with the image it produced not saved: the next "
            "start produces the one saved before",
            producer->plan().spec.name);
    }
}

void Exchanges::tick(core::MonoTime now, core::WallTime wall, bool refresh_scan) {
    // Every tick: each producer publishes its `_status` at its own phase of the second, so
    // that many of them never publish in one handler.
    for (auto& producer : producers_) producer->on_tick(now);
    // The summary of a flood of drops that stopped, which no next drop would log.
    router_.flush_log(now);
    for (auto& consumer : consumers_) consumer->on_tick(now, wall, refresh_scan);
}

void Exchanges::republish(core::MonoTime now, core::WallTime wall) {
    for (auto& consumer : consumers_) consumer->republish(now);
    for (auto& producer : producers_) producer->republish(wall);
}

std::optional<core::write::WriteRejection> Exchanges::stage(ExchangeWrite&& write,
                                                            const WriteReply& reply,
                                                            core::MonoTime now) {
    const auto found = by_handle_.find(write.producer);
    if (found == by_handle_.end()) {
        return core::write::WriteRejection{core::write::WriteError::unknown_tag,
                                           "the exchange is no longer produced"};
    }
    return found->second->stage(std::move(write.writes), reply, now);
}

bool Exchanges::holds(const ExchangeWrite& write) const {
    const auto found = by_handle_.find(write.producer);
    return found != by_handle_.end() && found->second->image().holds(write.writes);
}

ExchangeSet Exchanges::running() const {
    ExchangeSet running;
    running.consumed.reserve(consumers_.size());
    for (const auto& consumer : consumers_) running.consumed.push_back(&consumer->plan());
    running.produced.reserve(producers_.size());
    for (const auto& producer : producers_) running.produced.push_back(&producer->plan());
    return running;
}

std::vector<const core::plan::ExchangePlan*> Exchanges::running_plans() const {
    auto running_set = running();
    auto& plans = running_set.consumed;
    plans.insert(plans.end(), running_set.produced.begin(), running_set.produced.end());
    return plans;
}

}  // namespace eip2mqtt::app
