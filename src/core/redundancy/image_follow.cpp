#include "eip2mqtt/core/redundancy/image_follow.hpp"

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

}  // namespace eip2mqtt::core::redundancy
