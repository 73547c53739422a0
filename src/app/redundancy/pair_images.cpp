#include "eip2mqtt/app/redundancy/pair_images.hpp"

#include <spdlog/spdlog.h>

#include <utility>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/redundancy/image_message.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

using core::redundancy::FollowVerdict;

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
    publisher_.publish(std::move(message_));
    ++counters_.published;
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
