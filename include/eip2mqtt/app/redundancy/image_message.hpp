#pragma once
/// The payload of a pair's image topic (docs/schema/pair-image.json): a produced exchange's
/// image as the leader published it, as JSON.

#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/core/redundancy/image_follow.hpp"

namespace eip2mqtt::app::redundancy {

/// `{"id":"gw-a","epoch":3,"layout":"8c1f0e5a2b3d4c6e","data":"00803b45",
/// "answers":["5d2a…"],"refused":[]}`: the layout fingerprint and each answer key as 16 hex
/// digits (a JSON number loses precision above 2^53), the data bytes in hex, two digits each;
/// `answers` only when there is one, and `refused` with them when the image says it.
std::string encode_image_message(const core::redundancy::ImageMessage& image);

/// The image of a payload; nullopt for an empty one (a topic cleared by hand) or one that does
/// not read as an image.
std::optional<core::redundancy::ImageMessage> decode_image_message(std::string_view payload);

}  // namespace eip2mqtt::app::redundancy
