#pragma once
/// The standby's side of a pair's produced images (docs/redundancy.md): the leader publishes
/// the image of each produced exchange whenever a write changed it, and the standby judges each
/// one it reads before it takes it into its own producer, so that its first datagram after a
/// takeover carries the last written values. Pure: the unit's state is passed in.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::redundancy {

/// A produced image as the leader published it.
struct ImageMessage {
    std::string id;            ///< the publishing unit's gateway.id
    std::uint64_t epoch = 0;   ///< its lease's epoch when it published
    std::uint64_t layout = 0;  ///< the layout fingerprint of its exchange's image file
    std::vector<std::byte> data;
    /// The keys (answer_key.hpp) of the writes the publisher answered, or answers once the
    /// broker acknowledges this image, within the pair's write horizon: a standby taking over
    /// settles none of them again.
    std::vector<std::uint64_t> answers;
    /// The image's number among those its publisher published since it started (0: none, an
    /// older release's): the publisher knows its own image when the broker sends it back.
    std::uint64_t seq = 0;
    /// Those of `answers` that were refusals (`standby`: a write a new leader settled without
    /// holding it), a key once per refusal; the others were `ok`. nullopt in an older
    /// release's image, which does not say.
    std::optional<std::vector<std::uint64_t>> refused;

    friend bool operator==(const ImageMessage&, const ImageMessage&) = default;
};

/// What an image says a write listed in its `answers` was answered.
enum class ListedResult : std::uint8_t {
    ok,
    refused,  ///< `standby`
    unknown,  ///< an older release's image
};

/// One write an image lists as answered: its answer key and what it was answered.
struct ListedAnswer {
    std::uint64_t key = 0;
    ListedResult result = ListedResult::unknown;

    friend bool operator==(const ListedAnswer&, const ListedAnswer&) = default;
};

/// Each of `image`'s answers with its result, in the image's order: a key listed n times in
/// `refused` makes its first n listings refusals.
std::vector<ListedAnswer> listed_answers(const ImageMessage& image);

/// What the bytes of this unit's own image of the exchange mean.
struct ImageLayout {
    std::uint64_t fingerprint = 0;  ///< the same fingerprint as the image file's
    std::size_t length = 0;         ///< data bytes
};

/// What the unit reading an image message knows at that moment.
struct FollowContext {
    bool leading = false;
    /// The newest epoch its lease knows (Lease::epoch): the leader it follows, or its claim.
    std::uint64_t epoch = 0;
    /// Its own producer of the exchange the message names; nullopt when it produces none.
    std::optional<ImageLayout> producer;
};

/// What becomes of an image message.
enum class FollowVerdict : std::uint8_t {
    apply,             ///< the standby takes the image into its producer
    leading,           ///< this unit leads: its own image is the truth, never overwritten
    unknown_exchange,  ///< this unit produces no exchange of that topic
    other_layout,      ///< the two units' exchange differ in length, tag addresses or types
    stale,             ///< of an epoch older than this unit knows: a deposed leader's, late
};

inline constexpr auto follow_verdict_names =
    enum_names<FollowVerdict>("apply", "leading", "unknown_exchange", "other_layout", "stale");

constexpr std::string_view to_string(FollowVerdict verdict) {
    return follow_verdict_names.name_of(verdict);
}

/// Whether a standby takes `image` into its producer. A leader never does, whatever it reads
/// (its own retained images come back to it); a deposed leader's image that arrives after the
/// newer leader was heard is stale. An image of the current or a newer epoch is taken: a
/// retained image read at start-up may come before the leader's record, and the image of a
/// leader of before a restart of both units, whose epochs began again, is still the newest.
FollowVerdict judge_image(const ImageMessage& image, const FollowContext& context);

/// The request id that continues after `heard`, the last one heard from the other unit's
/// producer of the same exchange: one more, wrapping 65535 to 0 (docs/protocol.md §2).
constexpr std::uint16_t request_id_after(std::uint16_t heard) {
    return static_cast<std::uint16_t>(heard + 1);
}

}  // namespace eip2mqtt::core::redundancy
