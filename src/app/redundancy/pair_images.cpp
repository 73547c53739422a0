#include "eip2mqtt/app/redundancy/pair_images.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/redundancy/image_message.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

using core::redundancy::FollowVerdict;

/// An image's acknowledgement token: its number with the top bit set, which the lease's own
/// tokens (the time of a renewal in nanoseconds of the steady clock) never have.
constexpr std::uint64_t image_token_bit = std::uint64_t{1} << 63;

/// What this unit's image of `producer`'s exchange is, in the image file's own terms: an image
/// the other unit's file would not restore here is no image of this exchange either.
core::redundancy::ImageLayout layout_of(const ExchangeProducer& producer) {
    return {adapters::state::layout_fingerprint(producer.plan()), producer.plan().length};
}

}  // namespace

PairImages::PairImages(std::string prefix, std::string id, adapters::mqtt::Publisher& publisher)
    : prefix_(std::move(prefix)), id_(std::move(id)), publisher_(publisher) {}

std::string PairImages::topic_of(const core::plan::ExchangePlan& plan) const {
    return prefix_ + "/" + plan.spec.topic;
}

bool PairImages::owns(std::string_view topic) const {
    return topic.size() > prefix_.size() + 1 && topic.starts_with(prefix_) &&
           topic[prefix_.size()] == '/';
}

void PairImages::publish(const ExchangeProducer& producer, std::uint64_t epoch) {
    const auto data = producer.image().data();
    const core::redundancy::ImageMessage image{
        id_, epoch, layout_of(producer).fingerprint, {data.begin(), data.end()}};
    message_.topic = topic_of(producer.plan());
    message_.payload = encode_image_message(image);
    message_.qos = 1;
    message_.retain = true;
    const auto number = ++next_image_;
    message_.ack_token = image_token_bit | number;
    acks_[message_.topic].published = number;
    unacknowledged_.emplace(number, message_.topic);
    publisher_.publish(std::move(message_));
    ++counters_.published;
}

void PairImages::answer_after_image(const ExchangeProducer& producer,
                                    std::function<void()> answer) {
    auto topic = topic_of(producer.plan());
    const auto found = acks_.find(topic);
    if (found == acks_.end() || found->second.acknowledged >= found->second.published) {
        return answer();
    }
    waiting_.push_back({std::move(topic), found->second.published, std::move(answer)});
}

bool PairImages::on_acknowledged(std::uint64_t token, bool leading) {
    if ((token & image_token_bit) == 0) return false;
    const auto found = unacknowledged_.find(token & ~image_token_bit);
    if (found == unacknowledged_.end()) return true;
    const auto topic = found->second;
    auto& acks = acks_[topic];
    acks.acknowledged = std::max(acks.acknowledged, found->first);
    // Those it replaced in the queue were never sent: it stands for them.
    std::erase_if(unacknowledged_, [&](const auto& entry) {
        return entry.second == topic && entry.first <= acks.acknowledged;
    });
    // Most acknowledgements find no answer waiting: they build no queue.
    if (waiting_.empty()) return true;
    std::deque<Waiting> still;
    for (auto& waiting : waiting_) {
        if (waiting.topic != topic || waiting.through > acks.acknowledged) {
            still.push_back(std::move(waiting));
        } else if (leading) {
            waiting.answer();
        } else {
            ++counters_.answers_withheld;
        }
    }
    waiting_ = std::move(still);
    return true;
}

void PairImages::withhold_answers() {
    counters_.answers_withheld += waiting_.size();
    waiting_.clear();
}

std::optional<FollowVerdict> PairImages::on_message(
    const adapters::mqtt::Incoming& message,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, bool leading,
    std::uint64_t epoch) {
    const auto image = decode_image_message(message.payload);
    if (!image) {
        if (!message.payload.empty()) ++counters_.ignored_for(ImageIgnored::not_an_image);
        return std::nullopt;
    }
    const auto exchange_topic = std::string_view(message.topic).substr(prefix_.size() + 1);
    ExchangeProducer* producer = nullptr;
    for (const auto& candidate : producers) {
        if (candidate->plan().spec.topic == exchange_topic) producer = candidate.get();
    }
    core::redundancy::FollowContext context{leading, epoch, std::nullopt};
    if (producer) context.producer = layout_of(*producer);
    const auto verdict = core::redundancy::judge_image(*image, context);
    if (verdict == FollowVerdict::apply && !producer->follow_image(image->data)) return verdict;
    count(verdict, producer, *image);
    return verdict;
}

void PairImages::count(FollowVerdict verdict, const ExchangeProducer* producer,
                       const core::redundancy::ImageMessage& image) {
    switch (verdict) {
        case FollowVerdict::apply:
            ++counters_.followed;
            spdlog::debug("exchange {}: following the image of {} (epoch {})",
                          producer->plan().spec.name, image.id, image.epoch);
            return;
        case FollowVerdict::leading:
            return;
        case FollowVerdict::unknown_exchange:
            ++counters_.ignored_for(ImageIgnored::unknown_exchange);
            return;
        case FollowVerdict::stale:
            ++counters_.ignored_for(ImageIgnored::stale);
            return;
        case FollowVerdict::other_layout:
            ++counters_.ignored_for(ImageIgnored::other_layout);
            // A configuration that differs between the two units: said once, not per write.
            if (other_layout_logged_.insert(producer->plan().spec.name).second) {
                spdlog::warn(
                    "exchange {}: ignoring the images of {}, whose exchange has another layout "
                    "(length, tag addresses or types): a takeover produces this unit's own image",
                    producer->plan().spec.name, image.id);
            }
            return;
    }
}

}  // namespace eip2mqtt::app::redundancy
