#include "eip2mqtt/core/redundancy/image_follow.hpp"

#include <unordered_map>

namespace eip2mqtt::core::redundancy {

FollowVerdict judge_image(const ImageMessage& image, const FollowContext& context) {
    if (context.leading) return FollowVerdict::leading;
    if (!context.producer) return FollowVerdict::unknown_exchange;
    // The fingerprint covers the length too; the size check keeps a forged or corrupt message
    // from ever reaching the image with the wrong number of bytes.
    if (image.layout != context.producer->fingerprint ||
        image.data.size() != context.producer->length) {
        return FollowVerdict::other_layout;
    }
    if (image.epoch < context.epoch) return FollowVerdict::stale;
    return FollowVerdict::apply;
}

std::vector<ListedAnswer> listed_answers(const ImageMessage& image) {
    std::vector<ListedAnswer> listed;
    listed.reserve(image.answers.size());
    std::unordered_map<std::uint64_t, std::size_t> refusals;
    if (image.refused) {
        for (const auto key : *image.refused) ++refusals[key];
    }
    for (const auto key : image.answers) {
        auto result = image.refused ? ListedResult::ok : ListedResult::unknown;
        if (const auto found = refusals.find(key); found != refusals.end() && found->second > 0) {
            --found->second;
            result = ListedResult::refused;
        }
        listed.push_back({key, result});
    }
    return listed;
}

}  // namespace eip2mqtt::core::redundancy
