#pragma once
/// A pair's produced images at run time (README "Redundancy"): the leader publishes, on the
/// pair's own connection, the image of each produced exchange whenever writes changed it
/// (retained, QoS 1, a topic per exchange, so the newest image wins in the queue and on the
/// broker); the standby reads them and takes each one the rules allow
/// (core/redundancy/image_follow.hpp) into its own producer, which saves it as any image. So
/// the first datagram of a new leader carries the last written values. An image that cannot be
/// taken is counted by reason, and one of another layout logged once per exchange.
///
/// The leader answers a write `ok` only once the broker acknowledged the image carrying it
/// (answer_after_image): a standby that takes over then has that image, or the old leader
/// never said `ok` (the new one settles the write: PairWrites).
///
/// Threading: the loop only.

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/exchange_producer.hpp"
#include "eip2mqtt/core/redundancy/image_follow.hpp"

namespace eip2mqtt::app::redundancy {

/// Why a standby left an image aside: the index of PairImageCounters::ignored.
enum class ImageIgnored : std::uint8_t {
    other_layout,      ///< the exchange differs between the units
    stale,             ///< a deposed leader's, read late
    unknown_exchange,  ///< an exchange this unit does not produce
    not_an_image,      ///< a payload that does not read as an image
};

struct PairImageCounters {
    std::uint64_t published = 0;             ///< images this unit published as leader
    std::uint64_t followed = 0;              ///< images taken into a producer (a byte changed)
    std::array<std::uint64_t, 4> ignored{};  ///< by ImageIgnored
    /// Answers `ok` withheld: the unit stopped leading before the broker acknowledged the image
    /// carrying their write; the unit that takes over settles them.
    std::uint64_t answers_withheld = 0;

    std::uint64_t& ignored_for(ImageIgnored why) { return ignored[static_cast<std::size_t>(why)]; }
    std::uint64_t ignored_for(ImageIgnored why) const {
        return ignored[static_cast<std::size_t>(why)];
    }
};

class PairImages {
public:
    /// `prefix` is `{base}/_gateway/_pair/{pair}/image`, `id` this unit's gateway.id;
    /// `publisher` (the pair's connection) must outlive this.
    PairImages(std::string prefix, std::string id, adapters::mqtt::Publisher& publisher);

    /// `{prefix}/{exchange topic}`: the exchange's topic under the base is already a valid,
    /// unique topic of levels, where its name may hold anything.
    std::string topic_of(const core::plan::ExchangePlan& plan) const;
    /// Whether `topic` is one of the images'.
    bool owns(std::string_view topic) const;

    /// The leader: `producer`'s image as it stands, published as of lease epoch `epoch`.
    void publish(const ExchangeProducer& producer, std::uint64_t epoch);

    /// An image read on the pair's connection, judged and taken into the producer of its
    /// exchange among `producers` when the rules allow. `leading` and `epoch`: this unit's
    /// lease now. nullopt when the payload is no image (an empty one: a topic cleared by hand).
    std::optional<core::redundancy::FollowVerdict> on_message(
        const adapters::mqtt::Incoming& message,
        std::span<const std::unique_ptr<ExchangeProducer>> producers, bool leading,
        std::uint64_t epoch);

    /// The leader answers a write `ok` (`answer`) once no image of `producer`'s exchange it
    /// published so far waits for the broker's acknowledgement: now, or in on_acknowledged().
    void answer_after_image(const ExchangeProducer& producer, std::function<void()> answer);
    /// An acknowledgement of the pair's connection; false when `token` is no image's. The
    /// answers it releases are given while `leading`, withheld otherwise.
    bool on_acknowledged(std::uint64_t token, bool leading);
    /// This unit no longer leads: the answers waiting are withheld (counted).
    void withhold_answers();

    const PairImageCounters& counters() const { return counters_; }

private:
    /// Per image topic: the newest image published and the newest acknowledged (a newer image
    /// replaces an older one still queued, and its acknowledgement stands for both).
    struct Acks {
        std::uint64_t published = 0;
        std::uint64_t acknowledged = 0;
    };
    struct Waiting {
        std::string topic;
        std::uint64_t through = 0;  ///< waits for this image of `topic` to be acknowledged
        std::function<void()> answer;
    };

    void count(core::redundancy::FollowVerdict verdict, const ExchangeProducer* producer,
               const core::redundancy::ImageMessage& image);

    std::string prefix_;
    std::string id_;
    adapters::mqtt::Publisher& publisher_;
    PairImageCounters counters_;
    std::set<std::string> other_layout_logged_;  ///< exchange names
    adapters::mqtt::Message message_;
    std::uint64_t next_image_ = 0;
    std::unordered_map<std::string, Acks> acks_;
    std::map<std::uint64_t, std::string> unacknowledged_;  ///< image number -> topic
    std::deque<Waiting> waiting_;
};

}  // namespace eip2mqtt::app::redundancy
