#pragma once
/// The writes a pair's standby left to the leader (docs/redundancy.md, "Writes"), each kept
/// until the standby hears the leader's answer to it on the broker: the JSON tree's connection,
/// the one the writes come by, listens where writes are answered, `{set topic}/result` and
/// each left write's MQTT 5 response topic (response_topics(); JsonTree::set_answer_listener).
/// A response topic stays listened to for `topic_linger` after the last write left with it,
/// answered or not: the leader answers a write within milliseconds, often before a
/// subscription the write's arrival asked for reaches the broker, so a topic subscribed anew
/// for each write would miss answers, and the unit taking the lead would settle a write the
/// leader had answered (a second, contradicting answer). Only a topic's first write in a
/// linger, or one beyond `max_topics`, can still race its answer.
/// A unit that takes the lead settles the writes it heard no answer for and that the old
/// leader's images do not list as answered: the old leader died, hung or was cut off before
/// answering them, or never had them (WriteDispatcher::settle). The images are what a unit cut
/// off from the answers still hears: retained, the newest lists the answers of the horizon.
/// A write they list whose answer it did not hear, it answers again as listed: the old leader
/// may have died after the broker took the image and before its answer left, and a client
/// may get the same answer twice rather than none.
///
/// An answer is matched to the oldest write left with its topic and correlation data: writes to
/// one topic without correlation data cannot be told apart by their client either.
///
/// Threading: the loop only.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/redundancy/image_follow.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::redundancy {

struct PairWriteCounters {
    std::uint64_t answers_heard = 0;  ///< the leader's answers to writes this unit left
    /// Left writes the old leader's images listed as answered when this unit took the lead.
    std::uint64_t answers_listed = 0;
    /// Of those, the ones whose answer this unit gives again, as listed (ListedWrite).
    std::uint64_t answers_repeated = 0;
    /// Left writes forgotten unanswered: older than the horizon, or beyond the bound.
    std::uint64_t forgotten = 0;
};

/// A left write the old leader's images list as answered, with what they say it was answered.
struct ListedWrite {
    WriteRequest request;
    core::redundancy::ListedResult result = core::redundancy::ListedResult::unknown;
};

/// What a unit taking the lead does with the writes it left unanswered.
struct TakenWrites {
    std::vector<WriteRequest> unanswered;  ///< to settle (WriteDispatcher::settle)
    /// Listed as answered: answered again alike, unless the result is `unknown` (an older
    /// release's image).
    std::vector<ListedWrite> listed;
};

class PairWrites {
public:
    /// The most writes kept: only those of the last takeover window can matter, and a live
    /// leader answers every one.
    static constexpr std::size_t max_left = 1024;
    /// How long a response topic stays listened to after the last write left with it.
    static constexpr std::chrono::minutes topic_linger{10};
    /// The most response topics listened to: beyond, the one written least recently goes.
    static constexpr std::size_t max_topics = 64;

    /// `horizon`: how long a live leader may take to answer a write (its exchange's next
    /// production, the image's save, the broker's acknowledgement of the image); a write left
    /// longer ago is forgotten. `topics_changed` runs whenever response_topics() changed.
    PairWrites(std::chrono::milliseconds horizon, std::function<void()> topics_changed);

    /// A write this unit left to the leader, at `now`. One its northbound refused already
    /// (an invalid value, an unknown tag) is not kept: the leader refuses it alike, at once.
    void leave(WriteRequest&& request, core::MonoTime now);
    /// A message heard on an answer topic: the oldest write left with its topic and
    /// correlation data has its answer. Others (answers to writes not left here) are ignored.
    void heard(const adapters::mqtt::Incoming& answer);
    /// The response topics of the writes left within `topic_linger` (at most `max_topics`, the
    /// latest), to listen on besides `{set}/result`.
    std::vector<std::string> response_topics() const;
    /// This unit takes the lead: the writes kept that are within the horizon at `now` and were
    /// heard unanswered, oldest first, apart as the old leader's images list them answered or
    /// not (`listed`: PairImages::take_leader_answers; a key listed n times takes n writes, in
    /// order). None is kept afterwards, and no topic listened to.
    TakenWrites take_unanswered(core::MonoTime now,
                                std::span<const core::redundancy::ListedAnswer> listed);

    std::size_t size() const { return left_.size(); }
    const PairWriteCounters& counters() const { return counters_; }

private:
    struct Left {
        WriteRequest request;
        core::MonoTime at;
    };
    /// Forgets the writes left before `now - horizon`.
    void forget_older(core::MonoTime now);
    /// Listens on `topic`, a write's response topic, from `now` on; true when it is new.
    bool listen(const std::string& topic, core::MonoTime now);
    /// Stops listening on the topics lapsed at `now`; true when one went.
    bool forget_topics(core::MonoTime now);

    std::chrono::milliseconds horizon_;
    std::function<void()> topics_changed_;
    std::deque<Left> left_;
    std::map<std::string, core::MonoTime> topics_;  ///< response topic: last write left there
    PairWriteCounters counters_;
};

}  // namespace eip2mqtt::app::redundancy
