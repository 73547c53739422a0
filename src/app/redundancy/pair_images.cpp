#include "eip2mqtt/app/redundancy/pair_images.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/redundancy/image_message.hpp"
#include "eip2mqtt/core/redundancy/answer_key.hpp"

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

std::uint64_t key_of(const WriteReply& reply) {
    return core::redundancy::answer_key(reply.topic, reply.correlation_data);
}

}  // namespace

PairImages::PairImages(std::string prefix, std::string id, adapters::mqtt::Publisher& publisher,
                       std::chrono::milliseconds answers_kept)
    : prefix_(std::move(prefix)),
      id_(std::move(id)),
      publisher_(publisher),
      answers_kept_(answers_kept) {}

std::string PairImages::topic_of(const core::plan::ExchangePlan& plan) const {
    return prefix_ + "/" + plan.spec.topic;
}

bool PairImages::owns(std::string_view topic) const {
    return topic.size() > prefix_.size() + 1 && topic.starts_with(prefix_) &&
           topic[prefix_.size()] == '/';
}

void PairImages::publish(const ExchangeProducer& producer, std::uint64_t epoch) {
    message_.topic = topic_of(producer.plan());
    const auto data = producer.image().data();
    core::redundancy::ImageMessage image{
        id_, epoch, layout_of(producer).fingerprint, {data.begin(), data.end()}, {}};
    image.refused.emplace();
    for (const auto& answered : answers_[message_.topic]) {
        image.answers.push_back(answered.key);
        if (answered.refused) image.refused->push_back(answered.key);
    }
    const auto number = ++next_image_;
    image.seq = number;
    message_.payload = encode_image_message(image);
    message_.qos = 1;
    message_.retain = true;
    message_.ack_token = image_token_bit | number;
    acks_[message_.topic].published = number;
    unacknowledged_.emplace(number, message_.topic);
    epoch_ = epoch;
    publisher_.publish(std::move(message_));
    ++counters_.published;
}

bool PairImages::list_answer(const std::string& topic, std::uint64_t write_id, std::uint64_t key,
                             core::MonoTime now, bool refused) {
    auto& answers = answers_[topic];
    while (!answers.empty() &&
           (now - answers.front().at > answers_kept_ || answers.size() >= max_answers)) {
        answers.pop_front();
    }
    // Listed by the write, not its key: writes sharing a key (no correlation data) are each
    // listed, and a standby drops as many as the image lists.
    const bool listed = std::any_of(answers.begin(), answers.end(), [&](const Answered& answered) {
        return answered.write_id == write_id;
    });
    if (!listed) answers.push_back({write_id, key, now, refused});
    return !listed;
}

void PairImages::answer_after_image(const ExchangeProducer& producer, std::uint64_t write_id,
                                    const WriteReply& reply, core::MonoTime now,
                                    std::function<void()> answer) {
    auto topic = topic_of(producer.plan());
    const auto key = key_of(reply);
    if (list_answer(topic, write_id, key, now, false)) publish(producer, epoch_);
    // An image the broker never acknowledges (its connection dropped it) holds nothing forever.
    while (!waiting_.empty() && now - waiting_.front().since > answers_kept_) {
        withhold(std::move(waiting_.front()));
        waiting_.pop_front();
    }
    const auto& acks = acks_[topic];
    if (acks.acknowledged >= acks.published) return answer();
    waiting_.push_back({std::move(topic), acks.published, std::move(answer), now, epoch_,
                        stand_downs_, false, key});
}

template <class Decide>
void PairImages::release(const std::string& topic, std::uint64_t through, Decide&& decide) {
    // Most acknowledgements find no answer waiting: they build no queue.
    if (waiting_.empty()) return;
    std::deque<Waiting> still;
    for (auto& waiting : waiting_) {
        const auto verdict =
            waiting.topic != topic || waiting.through > through ? Release::wait : decide(waiting);
        switch (verdict) {
            case Release::wait:
                still.push_back(std::move(waiting));
                break;
            case Release::late:
                ++counters_.answers_late;
                waiting.answer();
                break;
            case Release::answer:
                waiting.answer();
                break;
            case Release::withhold:
                withhold(std::move(waiting));
                break;
        }
    }
    waiting_ = std::move(still);
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
    release(topic, acks.acknowledged, [&](Waiting& waiting) {
        if (leading && waiting.stand_downs == stand_downs_) return Release::answer;
        return waiting.reconnected ? Release::withhold : Release::wait;
    });
    return true;
}

void PairImages::heard_back(const std::string& topic, std::uint64_t seq, LeaseNow lease) {
    release(topic, seq, [&](Waiting& waiting) {
        if (lease.leading && waiting.stand_downs == stand_downs_) return Release::answer;
        if (waiting.reconnected) return Release::withhold;
        if (lease.others_epoch <= waiting.epoch) return Release::late;
        // A claim came first, but it may not stand: whether the claim that does stood before
        // or after the image decides (other_leads).
        waiting.claims_before = lease.others_epoch;
        return Release::withhold;
    });
}

void PairImages::other_leads(std::uint64_t epoch) {
    if (withheld_.empty() || epoch == 0) return;
    std::deque<Waiting> still;
    for (auto& waiting : withheld_) {
        if (waiting.claims_before == 0 || epoch <= waiting.epoch) {
            still.push_back(std::move(waiting));
        } else if (epoch > waiting.claims_before) {
            ++counters_.answers_late;
            waiting.answer();
        }
    }
    withheld_ = std::move(still);
}

void PairImages::withhold(Waiting&& waiting) {
    ++counters_.answers_withheld;
    withheld_.push_back(std::move(waiting));
}

void PairImages::answer_withheld(std::span<const core::redundancy::ListedAnswer> listed,
                                 core::MonoTime now, std::uint64_t others_led) {
    std::unordered_map<std::uint64_t, std::size_t> answered;
    for (const auto& answer : listed) ++answered[answer.key];
    auto withheld = std::move(withheld_);
    withheld_.clear();
    for (auto& waiting : withheld) {
        // Older than the horizon, with the other unit having led since: it forgot the write,
        // and whether it settled it, too. Had it not led, nobody answered the write.
        if (now - waiting.since > answers_kept_ && others_led > waiting.epoch) continue;
        const auto found = answered.find(waiting.key);
        if (found != answered.end() && found->second > 0) {
            --found->second;
            continue;
        }
        ++counters_.answers_late;
        waiting.answer();
    }
}

void PairImages::list_refusal(const core::plan::ExchangePlan& plan, std::uint64_t key,
                              core::MonoTime now) {
    list_answer(topic_of(plan), next_refusal_++, key, now, true);
}

void PairImages::reconnected() {
    for (auto& waiting : waiting_) waiting.reconnected = true;
}

std::optional<FollowVerdict> PairImages::on_message(
    const adapters::mqtt::Incoming& message,
    std::span<const std::unique_ptr<ExchangeProducer>> producers, LeaseNow lease) {
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
    // Sent back live, not a retained copy from before a restart or a reconnect.
    if (image->id == id_ && image->seq != 0 && !message.retained) {
        heard_back(std::string(message.topic), image->seq, lease);
    }
    core::redundancy::FollowContext context{lease.leading, lease.epoch, std::nullopt};
    if (producer) context.producer = layout_of(*producer);
    const auto verdict = core::redundancy::judge_image(*image, context);
    // Answers listed by the other unit's images that the broker took before this unit's
    // claim (read before the claim came back): a deposed leader's too, which gives them late
    // exactly then (other_leads).
    if (verdict != FollowVerdict::leading && !lease.claim_heard && image->id != id_) {
        heard_answers_[message.topic] = core::redundancy::listed_answers(*image);
    }
    if (verdict == FollowVerdict::apply && !producer->follow_image(image->data)) return verdict;
    count(verdict, producer, *image);
    return verdict;
}

std::vector<core::redundancy::ListedAnswer> PairImages::take_leader_answers() {
    std::vector<core::redundancy::ListedAnswer> answers;
    for (const auto& [topic, keys] : heard_answers_) {
        answers.insert(answers.end(), keys.begin(), keys.end());
    }
    heard_answers_.clear();
    return answers;
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
