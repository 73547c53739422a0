#include "eip2mqtt/app/redundancy/pair_writes.hpp"

#include <algorithm>
#include <set>
#include <utility>
#include <variant>

namespace eip2mqtt::app::redundancy {

PairWrites::PairWrites(std::chrono::milliseconds horizon, std::function<void()> topics_changed)
    : horizon_(horizon), topics_changed_(std::move(topics_changed)) {}

void PairWrites::leave(WriteRequest&& request, core::MonoTime now) {
    if (!std::holds_alternative<ExchangeWrite>(request.outcome)) return;
    bool changed = forget_older(now);
    if (left_.size() == max_left) {
        changed |= left_.front().response_topic;
        left_.pop_front();
        ++counters_.forgotten;
    }
    const bool response_topic = request.reply.topic != request.target + "/result";
    const bool new_topic =
        response_topic && std::none_of(left_.begin(), left_.end(), [&](const Left& left) {
            return left.request.reply.topic == request.reply.topic;
        });
    left_.push_back({std::move(request), now, response_topic});
    if ((changed || new_topic) && topics_changed_) topics_changed_();
}

void PairWrites::heard(const adapters::mqtt::Incoming& answer) {
    const auto found = std::find_if(left_.begin(), left_.end(), [&](const Left& left) {
        return left.request.reply.topic == answer.topic &&
               left.request.reply.correlation_data == answer.correlation_data;
    });
    if (found == left_.end()) return;
    const bool response_topic = found->response_topic;
    left_.erase(found);
    ++counters_.answers_heard;
    // The subscription goes with the last write answered there.
    if (response_topic && topics_changed_ &&
        std::none_of(left_.begin(), left_.end(),
                     [&](const Left& left) { return left.request.reply.topic == answer.topic; })) {
        topics_changed_();
    }
}

std::vector<std::string> PairWrites::response_topics() const {
    std::set<std::string> topics;
    for (const auto& left : left_) {
        if (left.response_topic) topics.insert(left.request.reply.topic);
    }
    return {topics.begin(), topics.end()};
}

std::vector<WriteRequest> PairWrites::take_unanswered(core::MonoTime now) {
    const bool topic_went = forget_older(now);
    std::vector<WriteRequest> unanswered;
    unanswered.reserve(left_.size());
    for (auto& left : left_) unanswered.push_back(std::move(left.request));
    const bool had_topics = std::any_of(left_.begin(), left_.end(),
                                        [](const Left& left) { return left.response_topic; });
    left_.clear();
    if ((topic_went || had_topics) && topics_changed_) topics_changed_();
    return unanswered;
}

bool PairWrites::forget_older(core::MonoTime now) {
    bool topic_went = false;
    while (!left_.empty() && now - left_.front().at > horizon_) {
        topic_went |= left_.front().response_topic;
        left_.pop_front();
        ++counters_.forgotten;
    }
    return topic_went;
}

}  // namespace eip2mqtt::app::redundancy
