#include "eip2mqtt/app/redundancy/pair_writes.hpp"

#include <algorithm>
#include <unordered_map>
#include <utility>
#include <variant>

#include "eip2mqtt/core/redundancy/answer_key.hpp"

namespace eip2mqtt::app::redundancy {

PairWrites::PairWrites(std::chrono::milliseconds horizon, std::function<void()> topics_changed)
    : horizon_(horizon), topics_changed_(std::move(topics_changed)) {}

void PairWrites::leave(WriteRequest&& request, core::MonoTime now) {
    if (!std::holds_alternative<ExchangeWrite>(request.outcome)) return;
    forget_older(now);
    bool changed = forget_topics(now);
    if (left_.size() == max_left) {
        left_.pop_front();
        ++counters_.forgotten;
    }
    if (request.reply.topic != request.target + "/result") {
        changed |= listen(request.reply.topic, now);
    }
    left_.push_back({std::move(request), now});
    if (changed && topics_changed_) topics_changed_();
}

void PairWrites::heard(const adapters::mqtt::Incoming& answer) {
    const auto found = std::find_if(left_.begin(), left_.end(), [&](const Left& left) {
        return left.request.reply.topic == answer.topic &&
               left.request.reply.correlation_data == answer.correlation_data;
    });
    if (found == left_.end()) return;
    left_.erase(found);
    ++counters_.answers_heard;
    // The topic stays listened to (topic_linger): the next write's answer may come before a
    // new subscription would.
}

std::vector<std::string> PairWrites::response_topics() const {
    std::vector<std::string> topics;
    topics.reserve(topics_.size());
    for (const auto& [topic, at] : topics_) topics.push_back(topic);
    return topics;
}

TakenWrites PairWrites::take_unanswered(core::MonoTime now,
                                        std::span<const core::redundancy::ListedAnswer> listed) {
    using core::redundancy::ListedResult;
    forget_older(now);
    std::unordered_map<std::uint64_t, std::deque<ListedResult>> answered;
    for (const auto& answer : listed) answered[answer.key].push_back(answer.result);
    TakenWrites taken;
    taken.unanswered.reserve(left_.size());
    for (auto& left : left_) {
        const auto& reply = left.request.reply;
        const auto found =
            answered.find(core::redundancy::answer_key(reply.topic, reply.correlation_data));
        if (found == answered.end() || found->second.empty()) {
            taken.unanswered.push_back(std::move(left.request));
            continue;
        }
        ++counters_.answers_listed;
        if (found->second.front() != ListedResult::unknown) ++counters_.answers_repeated;
        taken.listed.push_back({std::move(left.request), found->second.front()});
        found->second.pop_front();
    }
    left_.clear();
    const bool had_topics = !topics_.empty();
    topics_.clear();
    if (had_topics && topics_changed_) topics_changed_();
    return taken;
}

void PairWrites::forget_older(core::MonoTime now) {
    while (!left_.empty() && now - left_.front().at > horizon_) {
        left_.pop_front();
        ++counters_.forgotten;
    }
}

bool PairWrites::listen(const std::string& topic, core::MonoTime now) {
    const bool inserted = topics_.insert_or_assign(topic, now).second;
    if (inserted && topics_.size() > max_topics) {
        const auto oldest = std::min_element(topics_.begin(), topics_.end(), [&](auto& a, auto& b) {
            // The topic just listened to is the latest: never the one to go.
            return a.first != topic && (b.first == topic || a.second < b.second);
        });
        topics_.erase(oldest);
    }
    return inserted;
}

bool PairWrites::forget_topics(core::MonoTime now) {
    return std::erase_if(topics_,
                         [&](const auto& entry) { return now - entry.second > topic_linger; }) > 0;
}

}  // namespace eip2mqtt::app::redundancy
