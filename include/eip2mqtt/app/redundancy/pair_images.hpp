#pragma once
/// A pair's produced images at run time (docs/redundancy.md): the leader publishes, on the
/// pair's own connection, the image of each produced exchange whenever writes changed it
/// (retained, QoS 1, a topic per exchange, so the newest image wins in the queue and on the
/// broker); the standby reads them and takes each one the rules allow
/// (core/redundancy/image_follow.hpp) into its own producer, which saves it as any image. So
/// the first datagram of a new leader carries the last written values. An image that cannot be
/// taken is counted by reason, and one of another layout logged once per exchange.
///
/// The leader answers a write `ok` only once the broker acknowledged an image that lists the
/// write among its `answers` (answer_after_image; each image lists those of the write horizon
/// before it): a standby that takes over then has that image, and settles none of them again
/// (take_leader_answers(), PairWrites::take_unanswered), or the old leader never said `ok`
/// (the new one settles the write). The images say which answers were refusals, so the unit
/// taking over answers again, alike, a listed write whose answer it did not hear: the leader
/// may have died between the image's acknowledgement and its answer.
///
/// Threading: the loop only.

#include <array>
#include <chrono>
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
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/core/redundancy/image_follow.hpp"
#include "eip2mqtt/core/time.hpp"

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
    /// Answers `ok` withheld: the unit stopped leading, and another may have taken the lead,
    /// before the broker acknowledged the image listing their write; the unit that takes over
    /// settles them.
    std::uint64_t answers_withheld = 0;
    /// Answers given after the unit stopped leading: the broker acknowledged the image listing
    /// their write before any other unit claimed, so whoever leads next knows them answered.
    std::uint64_t answers_late = 0;

    std::uint64_t& ignored_for(ImageIgnored why) { return ignored[static_cast<std::size_t>(why)]; }
    std::uint64_t ignored_for(ImageIgnored why) const {
        return ignored[static_cast<std::size_t>(why)];
    }
};

class PairImages {
public:
    /// The most answers an image lists: beyond, the oldest goes (a write horizon's worth at
    /// tens of writes a second).
    static constexpr std::size_t max_answers = 1024;

    /// `prefix` is `{base}/_gateway/_pair/{pair}/image`, `id` this unit's gateway.id;
    /// `publisher` (the pair's connection) must outlive this. An answer stays listed for
    /// `answers_kept` (the pair's write horizon, PairWrites).
    PairImages(std::string prefix, std::string id, adapters::mqtt::Publisher& publisher,
               std::chrono::milliseconds answers_kept);

    /// `{prefix}/{exchange topic}`: the exchange's topic under the base is already a valid,
    /// unique topic of levels, where its name may hold anything.
    std::string topic_of(const core::plan::ExchangePlan& plan) const;
    /// Whether `topic` is one of the images'.
    bool owns(std::string_view topic) const;

    /// The leader: `producer`'s image as it stands, published as of lease epoch `epoch`, with
    /// the answers listed so far.
    void publish(const ExchangeProducer& producer, std::uint64_t epoch);

    /// This unit's lease as an image is read: its role and epoch, and the highest epoch the
    /// other unit claimed as heard so far (PairLease::others_epoch).
    struct LeaseNow {
        bool leading = false;
        std::uint64_t epoch = 0;
        std::uint64_t others_epoch = 0;
        /// This unit's claim was heard back (Lease::claim_heard_back): an image read after it
        /// came after the claim, and the unit that published it knows so.
        bool claim_heard = false;
    };
    /// An image read on the pair's connection, judged and taken into the producer of its
    /// exchange among `producers` when the rules allow. nullopt when the payload is no image
    /// (an empty one: a topic cleared by hand). This unit's own image, heard back live, gives
    /// the answers that waited for it: late, by a unit that stopped leading, only when no
    /// claim of the other unit was heard before it (the broker then took the image before any
    /// claim, and whoever leads next reads it before its claim stands); withheld otherwise.
    std::optional<core::redundancy::FollowVerdict> on_message(
        const adapters::mqtt::Incoming& message,
        std::span<const std::unique_ptr<ExchangeProducer>> producers, LeaseNow lease);

    /// The leader answers its write `write_id` of `producer`, to `reply`, `ok` (`answer`) once
    /// the broker acknowledged an image of the exchange that lists it, and every image
    /// published before: now, or in on_acknowledged(). The image is published again listing
    /// it, now, when the answer is due (its datagram sent, its image saved), not earlier: a
    /// leader that dies before has listed nothing it did not answer.
    void answer_after_image(const ExchangeProducer& producer, std::uint64_t write_id,
                            const WriteReply& reply, core::MonoTime now,
                            std::function<void()> answer);
    /// An acknowledgement of the pair's connection; false when `token` is no image's.
    /// `leading`: this unit's role now. The answers waiting for the image are given when the
    /// unit led throughout. One that stopped leading waits to hear the image back (on_message):
    /// an acknowledgement may overtake claims the broker took before the image and still
    /// holds for this connection. After a reconnect it withholds them.
    bool on_acknowledged(std::uint64_t token, bool leading);
    /// This unit no longer leads: the answers waiting are given only on the terms above.
    void stood_down() { ++stand_downs_; }
    /// The other unit was heard renewing under `epoch` (it leads): the answers this unit
    /// withheld on hearing a claim of the other unit before its image are given late when the
    /// claim that stood came after the image (`epoch` above those heard before it: the other
    /// unit read the image before it led, and settles none of its answers), and dropped
    /// otherwise (the other unit settled them). Cheap when nothing is withheld.
    void other_leads(std::uint64_t epoch);
    /// This unit takes the lead again: the answers it withheld are given, but for the writes
    /// the other unit's images list as answered (`listed`, from take_leader_answers(); each
    /// listing stands for one write), and those older than the horizon at `now` if the other
    /// unit led since (its images no longer say whether it settled them): `others_led` is the
    /// highest epoch the other unit was heard leading under (PairLease::others_renewed_epoch).
    void answer_withheld(std::span<const core::redundancy::ListedAnswer> listed, core::MonoTime now,
                         std::uint64_t others_led);
    /// The leader settled a write left to the old one by refusing it (WriteDispatcher::settle):
    /// its images list that answer too, `key`, so that no unit answers the write again.
    void list_refusal(const core::plan::ExchangePlan& plan, std::uint64_t key, core::MonoTime now);
    /// The pair's connection came back: what it waited for may have been sent again, after
    /// claims this unit did not hear before the acknowledgement.
    void reconnected();

    /// Taking the lead: the answers listed by the other unit's newest image of each exchange,
    /// with their results, as this unit heard them, forgotten here (its own images, read back
    /// retained, are not heard: they list answers it may have withheld).
    std::vector<core::redundancy::ListedAnswer> take_leader_answers();

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
        core::MonoTime since;
        std::uint64_t epoch = 0;        ///< of the images it waits for
        std::uint64_t stand_downs = 0;  ///< stand_downs_ when it began waiting
        bool reconnected = false;       ///< the connection came back since
        std::uint64_t key = 0;          ///< of its write's answer
        /// Heard back after claims of the other unit up to this epoch (withheld until it is
        /// known which claim stood: other_leads()); 0 when not heard back.
        std::uint64_t claims_before = 0;
    };
    struct Answered {
        std::uint64_t write_id = 0;  ///< in its producer: the answers are an exchange's
        std::uint64_t key = 0;
        core::MonoTime at;
        bool refused = false;  ///< `standby` (list_refusal), else `ok`
    };

    void count(core::redundancy::FollowVerdict verdict, const ExchangeProducer* producer,
               const core::redundancy::ImageMessage& image);
    /// Lists write `write_id`'s answer, `key`, among `topic`'s at `now`; false when it was
    /// already.
    bool list_answer(const std::string& topic, std::uint64_t write_id, std::uint64_t key,
                     core::MonoTime now, bool refused);
    /// The answers waiting for `topic`'s images up to `through`: each given, kept waiting or
    /// withheld as `decide(Waiting&) -> Release` says (defined where it is used: the .cpp).
    enum class Release : std::uint8_t { answer, late, wait, withhold };
    template <class Decide>
    void release(const std::string& topic, std::uint64_t through, Decide&& decide);
    /// This unit's own image heard back live (`seq` its number).
    void heard_back(const std::string& topic, std::uint64_t seq, LeaseNow lease);
    /// Keeps an answer withheld until this unit leads again (answer_withheld).
    void withhold(Waiting&& waiting);

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
    std::deque<Waiting> withheld_;
    std::uint64_t next_refusal_ = std::uint64_t{1} << 63;  ///< write ids no producer gives
    std::chrono::milliseconds answers_kept_;
    std::unordered_map<std::string, std::deque<Answered>> answers_;  ///< image topic: answers
    std::uint64_t epoch_ = 0;  ///< of the last image published
    std::uint64_t stand_downs_ = 0;
    /// The standby: image topic -> the answers of the other unit's newest image of it.
    std::unordered_map<std::string, std::vector<core::redundancy::ListedAnswer>> heard_answers_;
};

}  // namespace eip2mqtt::app::redundancy
